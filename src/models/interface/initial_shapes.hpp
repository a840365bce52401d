#pragma once
// Initial soil regions: boxes, circles (cylinders in 2D), polygons, and their union; and the
// fraction of a cell they cover.
#include <array>
#include <variant>
#include <vector>

namespace granflow::interface {

using Point = std::array<double, 2>;
struct Box {
  Point lower, upper;
};
struct Circle {
  Point centre;
  double radius;
};
struct Polygon {
  std::vector<Point> vertices;  // either orientation, not self-intersecting
};
using Shape = std::variant<Box, Circle, Polygon>;

bool contains(const Shape& shape, double x, double y);
// The smallest axis-aligned box around the shape: {lower, upper}.
std::array<Point, 2> bounding_box(const Shape& shape);
bool union_contains(const std::vector<Shape>& shapes, double x, double y);
// Whether the shape covers some area of the rectangle [lower, upper] (touching it is not enough).
bool overlaps(const Shape& shape, const Point& lower, const Point& upper);
// Whether two edges of the polygon that do not share a vertex cross or touch (a "bow tie").
bool self_intersecting(const Polygon& polygon);

// Fraction of the cell [x0,x1] x [y0,y1] inside the union, by samples x samples midpoint sampling
// (error O(1/samples) only in cells the boundary crosses). Axisymmetric (x = r >= 0): the fraction of
// the cell's volume, each sample weighted by its radius, so that a cut cell near the axis is not
// counted by its area.
double union_fraction(const std::vector<Shape>& shapes, double x0, double x1, double y0, double y1,
                      bool axisymmetric = false, int samples = 32);

}  // namespace granflow::interface

#pragma once
// Initial soil regions: boxes, circles (cylinders in 2D), rings, polygons, and their union; and the
// fraction of a cell they cover.
#include <array>
#include <cstddef>
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
// The annulus inner_radius <= |x - centre| <= outer_radius: a hollow cylinder in planar 2D; drawn in
// the r-z plane of an axisymmetric mesh, that section revolved about the axis (a torus where the
// annulus lies clear of the axis; the part at r < 0 is outside the mesh).
struct Ring {
  Point centre;
  double inner_radius, outer_radius;  // 0 < inner_radius < outer_radius
};
struct Polygon {
  std::vector<Point> vertices;  // either orientation, not self-intersecting
};
using Shape = std::variant<Box, Circle, Ring, Polygon>;

bool contains(const Shape& shape, double x, double y);
// The smallest axis-aligned box around the shape: {lower, upper}.
std::array<Point, 2> bounding_box(const Shape& shape);
// Every shape, every edge: the plain answer, which ShapeUnion gives faster on many points.
bool union_contains(const std::vector<Shape>& shapes, double x, double y);
// Whether the shape covers some area of the rectangle [lower, upper] (touching it is not enough).
bool overlaps(const Shape& shape, const Point& lower, const Point& upper);
// Whether two edges of the polygon that do not share a vertex cross or touch (a "bow tie").
bool self_intersecting(const Polygon& polygon);

// The union of shapes, prepared for the many point queries of laying them on a mesh: each shape's
// bounding box, and a polygon's edges binned by height, so that a query tests only the edges at its
// height instead of all of them (a terrain profile of 1e5 vertices costs a few edges per query).
// Answers are those of union_contains and the sampling below, bit for bit.
class ShapeUnion {
 public:
  explicit ShapeUnion(std::vector<Shape> shapes);
  bool contains(double x, double y) const;
  // Whether shape k alone contains the point.
  bool shape_contains(std::size_t k, double x, double y) const;
  std::size_t size() const { return shapes_.size(); }
  // Fraction of the cell [x0,x1] x [y0,y1] inside the union, by samples x samples midpoint sampling
  // (error O(1/samples) only in cells the boundary crosses). Axisymmetric (x = r >= 0): the fraction
  // of the cell's volume, each sample weighted by its radius, so that a cut cell near the axis is not
  // counted by its area.
  double fraction(double x0, double x1, double y0, double y1, bool axisymmetric = false, int samples = 32) const;
  // Whether a shape's outline may pass through the rectangle between its four corners and centre, so
  // that probing those five points could miss it: a box or circle narrower or lower than the
  // rectangle that reaches into it, a polygon's edge through it, a ring's band or hole narrower than
  // it. (A large circle's arc bulging through a side between two corners is not caught, and neither
  // is it by the probes: a sliver of the cell's area.)
  bool may_pass_between_probes(double x0, double x1, double y0, double y1) const;

 private:
  // A polygon's edges (edge e joins vertices e and e + 1) by height bin: bin b holds
  // edges[first[b] .. first[b + 1]), every edge whose height range meets the bin's.
  struct EdgeBins {
    double y_lower = 0.0, bins_per_metre = 0.0;
    int count = 0;
    std::vector<unsigned> first, edges;
    int bin(double y) const;
  };
  bool polygon_contains(const Polygon& p, const EdgeBins& bins, double x, double y) const;

  bool polygon_edge_through(std::size_t k, double x0, double x1, double y0, double y1) const;

  std::vector<Shape> shapes_;
  std::vector<std::array<Point, 2>> boxes_;
  std::vector<EdgeBins> bins_;  // empty for boxes and circles
};

}  // namespace granflow::interface

// Initial soil regions in 3D (y up, as in 2D): boxes, spheres, vertical cylinders (a granular column),
// and any 2D shape (initial_shapes.hpp) drawn in the x-y plane and extruded along z (a 2D case's block
// across a channel); their union, and the fraction of a cell they cover.
#pragma once

#include <array>
#include <cstddef>
#include <variant>
#include <vector>

#include "models/interface/initial_shapes.hpp"

namespace granflow::interface {

using Point3 = std::array<double, 3>;
struct Box3 {
  Point3 lower, upper;
};
struct Sphere {
  Point3 centre;
  double radius;
};
// The column of radius `radius` about the vertical line through (x, z) = centre_xz, from y = bottom to top.
struct VerticalCylinder {
  std::array<double, 2> centre_xz;
  double radius;
  double bottom, top;
};
// The 2D shape's section, for z in [z_lower, z_upper].
struct Extrusion {
  Shape section;
  double z_lower, z_upper;
};
using Shape3 = std::variant<Box3, Sphere, VerticalCylinder, Extrusion>;

bool contains(const Shape3& shape, double x, double y, double z);
// The smallest axis-aligned box around the shape: {lower, upper}.
std::array<Point3, 2> bounding_box(const Shape3& shape);

// The union of shapes, laid on a mesh: point queries, and the fraction of a cell.
class ShapeUnion3 {
 public:
  explicit ShapeUnion3(std::vector<Shape3> shapes);
  bool contains(double x, double y, double z) const;
  bool shape_contains(std::size_t k, double x, double y, double z) const;  // shape k alone
  std::size_t size() const { return shapes_.size(); }
  // Fraction of the cell [lower, upper] inside the union, by samples^3 midpoint sampling where the
  // cell's eight corners and centre disagree or a shape's outline may pass between them (error
  // O(1/samples) in those cells). As in 2D, a large sphere's or cylinder's surface bulging through a
  // face of the cell between its probes is not caught: a sliver of the cell's volume.
  double fraction(const Point3& lower, const Point3& upper, int samples = 16) const;

 private:
  std::vector<Shape3> shapes_;
  std::vector<std::array<Point3, 2>> boxes_;
  std::vector<ShapeUnion> sections_;  // an extrusion's section, prepared; empty for the others
};

}  // namespace granflow::interface

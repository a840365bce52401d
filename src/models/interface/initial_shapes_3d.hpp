// Initial soil regions in 3D (y up, as in 2D): boxes, spheres, vertical cylinders (a granular column),
// the ground under a height map (terrain from an elevation model), and any 2D shape (initial_shapes.hpp)
// drawn in the x-y plane and extruded along z (a 2D case's block across a channel); their union, and
// the fraction of a cell they cover.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
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
// The ground under a surface y = h(x, z) given at the nodes of a regular grid over x and z (a terrain's
// digital elevation model), bilinear between the nodes: the points from `bottom` up to the surface over
// the grid's extent, which reaches half a spacing beyond the outer nodes (each node stands for the cell
// of the grid around it, as an elevation model's cells do), the surface there level with them.
struct HeightMap {
  std::array<double, 2> origin{0.0, 0.0};   // x and z of the first node, m
  std::array<double, 2> spacing{1.0, 1.0};  // between nodes along x and z, m
  int nx = 0, nz = 0;                       // nodes along x and z, at least 2 each
  std::vector<double> heights;              // nx * nz, x fastest: node (i, r) at (origin + (i dx, r dz))
  double bottom = -std::numeric_limits<double>::infinity();
};
// h(x, z): bilinear in the grid's cell that holds (x, z); beyond the outer nodes, theirs.
double surface_height(const HeightMap& map, double x, double z);

// The map cut down to the nodes the surface takes over [x_range] x [z_range] (those of the grid's cells
// that reach into it, at least two along each axis): the same heights there. A map that does not reach
// the ranges is returned whole.
HeightMap cropped(const HeightMap& map, std::array<double, 2> x_range, std::array<double, 2> z_range);

using Shape3 = std::variant<Box3, Sphere, VerticalCylinder, Extrusion, HeightMap>;

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
  // cell's eight corners and centre disagree or a shape's outline may pass between them, as in every
  // cell a height map's surface may cross (error O(1/samples) in those cells). As in 2D, a large
  // sphere's or cylinder's surface bulging through a face of the cell between its probes is not
  // caught: a sliver of the cell's volume.
  double fraction(const Point3& lower, const Point3& upper, int samples = 16) const;

 private:
  std::vector<Shape3> shapes_;
  std::vector<std::array<Point3, 2>> boxes_;
  std::vector<ShapeUnion> sections_;  // an extrusion's section, prepared; empty for the others
};

}  // namespace granflow::interface

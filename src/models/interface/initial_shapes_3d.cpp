#include "models/interface/initial_shapes_3d.hpp"

#include <algorithm>
#include <cmath>

namespace granflow::interface {

double surface_height(const HeightMap& map, double x, double z) {
  // Grid units, held at the outer nodes (the half cell beyond them takes their heights); the cell of the
  // grid, the last node's line belonging to the cell before it.
  const double u = std::clamp((x - map.origin[0]) / map.spacing[0], 0.0, double(map.nx - 1));
  const double w = std::clamp((z - map.origin[1]) / map.spacing[1], 0.0, double(map.nz - 1));
  const int i = std::min(int(u), map.nx - 2), r = std::min(int(w), map.nz - 2);
  const double a = u - i, b = w - r;
  const double* row = map.heights.data() + size_t(r) * map.nx + i;
  const double low = row[0] + a * (row[1] - row[0]), high = row[map.nx] + a * (row[map.nx + 1] - row[map.nx]);
  return low + b * (high - low);
}

namespace {
// The first and last node along x (axis 0) or z (1) of the grid cells that reach into [from, to] (the
// heights between them take), clamped to the grid; {0, -1} where none does.
std::array<int, 2> node_span(const HeightMap& map, int axis, std::array<double, 2> range) {
  const int n = axis == 0 ? map.nx : map.nz;
  const double o = map.origin[axis], d = map.spacing[axis];
  const double first = std::floor((range[0] - o) / d), last = std::ceil((range[1] - o) / d);
  if (!(last >= 0.0 && first <= n - 1)) return {0, -1};
  return {int(std::max(first, 0.0)), int(std::min(last, double(n - 1)))};
}
}  // namespace

HeightMap cropped(const HeightMap& map, std::array<double, 2> x_range, std::array<double, 2> z_range) {
  auto nodes = [&](std::array<double, 2> range, int axis) {
    auto out = node_span(map, axis, range);
    if (out[1] == out[0]) {  // at least two nodes
      if (out[0] > 0) --out[0];
      else ++out[1];
    }
    return out;
  };
  const auto xi = nodes(x_range, 0), zr = nodes(z_range, 1);
  if (xi[1] < xi[0] || zr[1] < zr[0]) return map;
  HeightMap out = map;
  out.nx = xi[1] - xi[0] + 1;
  out.nz = zr[1] - zr[0] + 1;
  out.origin = {map.origin[0] + xi[0] * map.spacing[0], map.origin[1] + zr[0] * map.spacing[1]};
  out.heights.clear();
  for (int r = zr[0]; r <= zr[1]; ++r)
    for (int i = xi[0]; i <= xi[1]; ++i) out.heights.push_back(map.heights[size_t(r) * map.nx + i]);
  return out;
}

namespace {
// The map's extent along x (0) or z (1): its nodes' and half a spacing beyond the outer ones, as each
// node of an elevation model stands for the cell of the grid around it.
std::array<double, 2> extent(const HeightMap& map, int axis) {
  const int n = axis == 0 ? map.nx : map.nz;
  const double half = 0.5 * map.spacing[axis];
  return {map.origin[axis] - half, map.origin[axis] + (n - 1) * map.spacing[axis] + half};
}

// The lowest and highest heights the surface takes over [x0, x1] x [z0, z1] (within the extent): those
// of the nodes of the grid's cells that overlap it, since bilinear values lie between their cell's nodes'.
std::array<double, 2> surface_range(const HeightMap& m, double x0, double x1, double z0, double z1) {
  const auto ci = node_span(m, 0, {x0, x1}), cr = node_span(m, 1, {z0, z1});
  std::array<double, 2> range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (int r = cr[0]; r <= cr[1]; ++r)
    for (int i = ci[0]; i <= ci[1]; ++i) {
      const double h = m.heights[size_t(r) * m.nx + i];
      range = {std::min(range[0], h), std::max(range[1], h)};
    }
  return range;
}

struct Contains3 {
  double x, y, z;
  bool operator()(const Box3& b) const {
    return x >= b.lower[0] && x <= b.upper[0] && y >= b.lower[1] && y <= b.upper[1] && z >= b.lower[2] &&
           z <= b.upper[2];
  }
  bool operator()(const Sphere& s) const {
    const double dx = x - s.centre[0], dy = y - s.centre[1], dz = z - s.centre[2];
    return dx * dx + dy * dy + dz * dz <= s.radius * s.radius;
  }
  bool operator()(const VerticalCylinder& c) const {
    const double dx = x - c.centre_xz[0], dz = z - c.centre_xz[1];
    return y >= c.bottom && y <= c.top && dx * dx + dz * dz <= c.radius * c.radius;
  }
  bool operator()(const Extrusion& e) const {
    return z >= e.z_lower && z <= e.z_upper && interface::contains(e.section, x, y);
  }
  bool operator()(const HeightMap& m) const {
    const auto ex = extent(m, 0), ez = extent(m, 1);
    return x >= ex[0] && x <= ex[1] && z >= ez[0] && z <= ez[1] && y >= m.bottom && y <= surface_height(m, x, z);
  }
};
}  // namespace

bool contains(const Shape3& shape, double x, double y, double z) { return std::visit(Contains3{x, y, z}, shape); }

std::array<Point3, 2> bounding_box(const Shape3& shape) {
  if (const auto* b = std::get_if<Box3>(&shape)) return {b->lower, b->upper};
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    const double r = s->radius;
    return {Point3{s->centre[0] - r, s->centre[1] - r, s->centre[2] - r},
            Point3{s->centre[0] + r, s->centre[1] + r, s->centre[2] + r}};
  }
  if (const auto* c = std::get_if<VerticalCylinder>(&shape))
    return {Point3{c->centre_xz[0] - c->radius, c->bottom, c->centre_xz[1] - c->radius},
            Point3{c->centre_xz[0] + c->radius, c->top, c->centre_xz[1] + c->radius}};
  if (const auto* m = std::get_if<HeightMap>(&shape)) {
    const auto ex = extent(*m, 0), ez = extent(*m, 1);
    return {Point3{ex[0], m->bottom, ez[0]},
            Point3{ex[1], *std::max_element(m->heights.begin(), m->heights.end()), ez[1]}};
  }
  const auto& e = std::get<Extrusion>(shape);
  const auto [lo, hi] = bounding_box(e.section);
  return {Point3{lo[0], lo[1], e.z_lower}, Point3{hi[0], hi[1], e.z_upper}};
}

ShapeUnion3::ShapeUnion3(std::vector<Shape3> shapes) : shapes_(std::move(shapes)) {
  for (const auto& s : shapes_) {
    boxes_.push_back(bounding_box(s));
    const auto* e = std::get_if<Extrusion>(&s);
    sections_.emplace_back(e ? std::vector<Shape>{e->section} : std::vector<Shape>{});
  }
}

bool ShapeUnion3::shape_contains(std::size_t k, double x, double y, double z) const {
  const auto& [lo, hi] = boxes_[k];
  if (x < lo[0] || x > hi[0] || y < lo[1] || y > hi[1] || z < lo[2] || z > hi[2]) return false;
  return std::holds_alternative<Extrusion>(shapes_[k]) ? sections_[k].contains(x, y)  // within the box, so the z range
                                                       : interface::contains(shapes_[k], x, y, z);
}

bool ShapeUnion3::contains(double x, double y, double z) const {
  for (std::size_t k = 0; k < shapes_.size(); ++k)
    if (shape_contains(k, x, y, z)) return true;
  return false;
}

double ShapeUnion3::fraction(const Point3& lower, const Point3& upper, int samples) const {
  // Fast path: the eight corners and the centre agree, and no shape is small enough here to pass
  // between them: one narrower than the cell along an axis and reaching into it, or an extruded
  // section whose outline may pass through the cell's x-y rectangle between the probes (a notch
  // narrower than the cell; ShapeUnion::may_pass_between_probes).
  bool small_shape_here = false;
  for (std::size_t k = 0; k < shapes_.size() && !small_shape_here; ++k) {
    const auto& [lo, hi] = boxes_[k];
    bool overlaps = true;
    for (int a = 0; a < 3; ++a) overlaps = overlaps && lo[a] < upper[a] && hi[a] > lower[a];
    if (!overlaps) continue;
    for (int a = 0; a < 3; ++a) small_shape_here = small_shape_here || hi[a] - lo[a] < upper[a] - lower[a];
    if (!small_shape_here && std::holds_alternative<Extrusion>(shapes_[k]))
      small_shape_here = sections_[k].may_pass_between_probes(lower[0], upper[0], lower[1], upper[1]);
    if (const auto* m = std::get_if<HeightMap>(&shapes_[k]); m && !small_shape_here) {
      // The surface may rise or dip between the probes (a grid finer than the cell): sampled wherever
      // its heights over the cell reach into the cell's.
      const auto h = surface_range(*m, std::max(lower[0], lo[0]), std::min(upper[0], hi[0]), std::max(lower[2], lo[2]),
                                   std::min(upper[2], hi[2]));
      small_shape_here = h[0] < upper[1] && h[1] > lower[1];
    }
  }
  int probe = contains(0.5 * (lower[0] + upper[0]), 0.5 * (lower[1] + upper[1]), 0.5 * (lower[2] + upper[2]));
  for (int c = 0; c < 8; ++c)
    probe += contains(c & 1 ? upper[0] : lower[0], c & 2 ? upper[1] : lower[1], c & 4 ? upper[2] : lower[2]);
  if (!small_shape_here && probe == 0) return 0.0;
  if (!small_shape_here && probe == 9) return 1.0;
  long inside = 0;
  for (int c = 0; c < samples; ++c) {
    const double z = lower[2] + (c + 0.5) * (upper[2] - lower[2]) / samples;
    for (int b = 0; b < samples; ++b) {
      const double y = lower[1] + (b + 0.5) * (upper[1] - lower[1]) / samples;
      for (int a = 0; a < samples; ++a) inside += contains(lower[0] + (a + 0.5) * (upper[0] - lower[0]) / samples, y, z);
    }
  }
  return double(inside) / (double(samples) * samples * samples);
}

}  // namespace granflow::interface

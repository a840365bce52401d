#include "models/interface/initial_shapes.hpp"

#include <algorithm>
#include <cstddef>

namespace granflow::interface {

namespace {
struct Contains {
  double x, y;
  bool operator()(const Box& b) const { return x >= b.lower[0] && x <= b.upper[0] && y >= b.lower[1] && y <= b.upper[1]; }
  bool operator()(const Circle& c) const {
    const double dx = x - c.centre[0], dy = y - c.centre[1];
    return dx * dx + dy * dy <= c.radius * c.radius;
  }
  bool operator()(const Polygon& p) const {  // even-odd crossing rule
    bool inside = false;
    const std::size_t n = p.vertices.size();
    for (std::size_t a = 0, b = n - 1; a < n; b = a++) {
      const Point& pa = p.vertices[a];
      const Point& pb = p.vertices[b];
      if ((pa[1] > y) != (pb[1] > y) && x < (pb[0] - pa[0]) * (y - pa[1]) / (pb[1] - pa[1]) + pa[0]) inside = !inside;
    }
    return inside;
  }
};
}  // namespace

bool contains(const Shape& shape, double x, double y) { return std::visit(Contains{x, y}, shape); }

std::array<Point, 2> bounding_box(const Shape& shape) {
  if (const auto* b = std::get_if<Box>(&shape)) return {b->lower, b->upper};
  if (const auto* c = std::get_if<Circle>(&shape))
    return {Point{c->centre[0] - c->radius, c->centre[1] - c->radius}, Point{c->centre[0] + c->radius, c->centre[1] + c->radius}};
  const auto& v = std::get<Polygon>(shape).vertices;
  std::array<Point, 2> box{v.front(), v.front()};
  for (const auto& p : v)
    for (int a = 0; a < 2; ++a) {
      box[0][a] = std::min(box[0][a], p[a]);
      box[1][a] = std::max(box[1][a], p[a]);
    }
  return box;
}

bool union_contains(const std::vector<Shape>& shapes, double x, double y) {
  for (const auto& s : shapes)
    if (contains(s, x, y)) return true;
  return false;
}

double union_fraction(const std::vector<Shape>& shapes, double x0, double x1, double y0, double y1, int samples) {
  // Fast path: the four corners and the centre agree (cells are small against the shapes).
  const int probe = union_contains(shapes, x0, y0) + union_contains(shapes, x1, y0) + union_contains(shapes, x0, y1) +
                    union_contains(shapes, x1, y1) + union_contains(shapes, 0.5 * (x0 + x1), 0.5 * (y0 + y1));
  if (probe == 0) return 0.0;
  if (probe == 5) return 1.0;
  int hits = 0;
  for (int a = 0; a < samples; ++a)
    for (int b = 0; b < samples; ++b) {
      const double x = x0 + (a + 0.5) * (x1 - x0) / samples;
      const double y = y0 + (b + 0.5) * (y1 - y0) / samples;
      hits += union_contains(shapes, x, y);
    }
  return double(hits) / (samples * samples);
}

}  // namespace granflow::interface

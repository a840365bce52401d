#include "models/interface/initial_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace granflow::interface {

namespace {
struct Contains {
  double x, y;
  bool operator()(const Box& b) const { return x >= b.lower[0] && x <= b.upper[0] && y >= b.lower[1] && y <= b.upper[1]; }
  bool operator()(const Circle& c) const {
    const double dx = x - c.centre[0], dy = y - c.centre[1];
    return dx * dx + dy * dy <= c.radius * c.radius;
  }
  bool operator()(const Ring& r) const {
    const double dx = x - r.centre[0], dy = y - r.centre[1], d2 = dx * dx + dy * dy;
    return d2 >= r.inner_radius * r.inner_radius && d2 <= r.outer_radius * r.outer_radius;
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
  if (const auto* r = std::get_if<Ring>(&shape)) return bounding_box(Circle{r->centre, r->outer_radius});
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

namespace {
// Orientation of c against the line a -> b: > 0 left, < 0 right, 0 on it.
double orient(const Point& a, const Point& b, const Point& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}
bool on_segment(const Point& a, const Point& b, const Point& c) {  // c on the line ab: within its extent?
  return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
         c[1] <= std::max(a[1], b[1]);
}
// Segments ab and cd cross or touch.
bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}
}  // namespace

bool overlaps(const Shape& shape, const Point& lower, const Point& upper) {
  if (const auto* b = std::get_if<Box>(&shape))
    return b->lower[0] < upper[0] && b->upper[0] > lower[0] && b->lower[1] < upper[1] && b->upper[1] > lower[1];
  if (const auto* c = std::get_if<Circle>(&shape)) {
    const double dx = c->centre[0] - std::clamp(c->centre[0], lower[0], upper[0]);
    const double dy = c->centre[1] - std::clamp(c->centre[1], lower[1], upper[1]);
    return dx * dx + dy * dy < c->radius * c->radius;
  }
  if (const auto* r = std::get_if<Ring>(&shape)) {
    // The outer disc covers some of the rectangle, and the hole not all of it: the rectangle is convex,
    // so between a point of it inside the outer disc and one outside the (closed) hole lie points of
    // the open annulus, with area around them. The hole, a disc, holds the rectangle if it holds its corners.
    if (!overlaps(Circle{r->centre, r->outer_radius}, lower, upper)) return false;
    for (const double x : {lower[0], upper[0]})
      for (const double y : {lower[1], upper[1]}) {
        const double dx = x - r->centre[0], dy = y - r->centre[1];
        if (dx * dx + dy * dy > r->inner_radius * r->inner_radius) return true;
      }
    return false;
  }
  // A polygon: the area of its part inside the rectangle, clipped edge by edge (Sutherland-Hodgman,
  // which keeps the area of a concave polygon right though it may leave edges along the sides).
  std::vector<Point> clipped = std::get<Polygon>(shape).vertices;
  for (int axis = 0; axis < 2; ++axis)
    for (double side : {-1.0, 1.0}) {
      const double bound = side < 0 ? lower[axis] : upper[axis];
      const auto inside = [&](const Point& p) { return side * (p[axis] - bound) <= 0.0; };
      std::vector<Point> next;
      for (std::size_t k = 0; k < clipped.size(); ++k) {
        const Point& p = clipped[k];
        const Point& q = clipped[(k + 1) % clipped.size()];
        if (inside(p)) next.push_back(p);
        if (inside(p) != inside(q)) {
          const double t = (bound - p[axis]) / (q[axis] - p[axis]);
          next.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
        }
      }
      clipped.swap(next);
      if (clipped.empty()) return false;
    }
  double twice_area = 0.0;
  for (std::size_t k = 0; k < clipped.size(); ++k) {
    const Point& p = clipped[k];
    const Point& q = clipped[(k + 1) % clipped.size()];
    twice_area += p[0] * q[1] - q[0] * p[1];
  }
  return std::abs(twice_area) > 1e-12 * (upper[0] - lower[0]) * (upper[1] - lower[1]);
}

bool self_intersecting(const Polygon& polygon) {
  const auto& v = polygon.vertices;
  const std::size_t n = v.size();
  // Sweep in x: edges taken in the order of their left ends, each tested against the edges still
  // open there (whose right end is not left of it). Edges far apart in x are never compared, so a
  // profile of many vertices is checked in about n log n, not n^2.
  auto left = [&](std::size_t e) { return std::min(v[e][0], v[(e + 1) % n][0]); };
  auto right = [&](std::size_t e) { return std::max(v[e][0], v[(e + 1) % n][0]); };
  std::vector<std::size_t> order(n);
  for (std::size_t e = 0; e < n; ++e) order[e] = e;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return left(a) < left(b); });
  std::vector<std::size_t> open;
  for (const std::size_t a : order) {
    const double x = left(a);
    std::erase_if(open, [&](std::size_t b) { return right(b) < x; });
    for (const std::size_t b : open) {
      const bool adjacent = (a + 1) % n == b || (b + 1) % n == a;
      if (adjacent) continue;
      if (segments_meet(v[a], v[(a + 1) % n], v[b], v[(b + 1) % n])) return true;
    }
    open.push_back(a);
  }
  return false;
}

ShapeUnion::ShapeUnion(std::vector<Shape> shapes) : shapes_(std::move(shapes)) {
  for (const auto& s : shapes_) {
    boxes_.push_back(bounding_box(s));
    EdgeBins bins;
    if (const auto* p = std::get_if<Polygon>(&s)) {
      const auto& v = p->vertices;
      const std::size_t n = v.size();
      const auto [lo, hi] = boxes_.back();
      bins.y_lower = lo[1];
      // As many bins as edges, fewer where tall edges would be listed in too many of them (a comb
      // of spikes): at most about 8 entries per edge.
      for (std::size_t count = std::min<std::size_t>(n, 1 << 16);; count = std::max<std::size_t>(count / 2, 1)) {
        bins.count = int(count);
        // One bin for a polygon of no height, or of a height beyond what a double holds.
        const double per_metre = double(count) / (hi[1] - lo[1]);
        bins.bins_per_metre = hi[1] > lo[1] && std::isfinite(per_metre) && per_metre > 0.0 ? per_metre : 0.0;
        if (bins.bins_per_metre == 0.0) bins.count = int(count = 1);
        std::size_t entries = 0;
        for (std::size_t e = 0; e < n; ++e) {
          const auto [a, b] = std::minmax(v[e][1], v[(e + 1) % n][1]);
          entries += std::size_t(bins.bin(b) - bins.bin(a) + 1);
        }
        if (entries <= 8 * n + count || count == 1) break;
      }
      // Counting sort of the edges into their bins.
      bins.first.assign(std::size_t(bins.count) + 1, 0);
      for (std::size_t e = 0; e < n; ++e) {
        const auto [a, b] = std::minmax(v[e][1], v[(e + 1) % n][1]);
        for (int k = bins.bin(a); k <= bins.bin(b); ++k) ++bins.first[std::size_t(k) + 1];
      }
      for (std::size_t k = 0; k < std::size_t(bins.count); ++k) bins.first[k + 1] += bins.first[k];
      bins.edges.resize(bins.first.back());
      std::vector<unsigned> next(bins.first.begin(), bins.first.end() - 1);
      for (std::size_t e = 0; e < n; ++e) {
        const auto [a, b] = std::minmax(v[e][1], v[(e + 1) % n][1]);
        for (int k = bins.bin(a); k <= bins.bin(b); ++k) bins.edges[next[std::size_t(k)]++] = unsigned(e);
      }
    }
    bins_.push_back(std::move(bins));
  }
}

// Monotone in y, so an edge listed in the bins of its lowest and highest points and those between
// is in the bin of every height it spans.
int ShapeUnion::EdgeBins::bin(double y) const {
  const double b = std::floor((y - y_lower) * bins_per_metre);
  return !(b > 0.0) ? 0 : b >= count - 1 ? count - 1 : int(b);  // NaN to the first bin
}

// The even-odd rule of contains(), over the edges of the query's height bin only. An edge that
// changes the parity has one end above y and one at or below it, so it spans y and is in that bin;
// the parity does not depend on the order the edges are taken in.
bool ShapeUnion::polygon_contains(const Polygon& p, const EdgeBins& bins, double x, double y) const {
  const auto& v = p.vertices;
  const std::size_t n = v.size();
  const int k = bins.bin(y);
  bool inside = false;
  for (unsigned q = bins.first[std::size_t(k)]; q < bins.first[std::size_t(k) + 1]; ++q) {
    const std::size_t a = (bins.edges[q] + 1) % n, b = bins.edges[q];  // as contains(): a follows b
    const Point& pa = v[a];
    const Point& pb = v[b];
    if ((pa[1] > y) != (pb[1] > y) && x < (pb[0] - pa[0]) * (y - pa[1]) / (pb[1] - pa[1]) + pa[0]) inside = !inside;
  }
  return inside;
}

bool ShapeUnion::shape_contains(std::size_t k, double x, double y) const {
  if (const auto* p = std::get_if<Polygon>(&shapes_[k])) return polygon_contains(*p, bins_[k], x, y);
  return interface::contains(shapes_[k], x, y);
}

bool ShapeUnion::contains(double x, double y) const {
  for (std::size_t k = 0; k < shapes_.size(); ++k)
    if (shape_contains(k, x, y)) return true;
  return false;
}

// Whether an edge of polygon k passes through the open rectangle (x0, x1) x (y0, y1): the part of
// the segment inside the rectangle's slab along each axis (Liang & Barsky), of non-zero length.
bool ShapeUnion::polygon_edge_through(std::size_t k, double x0, double x1, double y0, double y1) const {
  const auto& v = std::get<Polygon>(shapes_[k]).vertices;
  const std::size_t n = v.size();
  const EdgeBins& bins = bins_[k];
  for (int b = bins.bin(y0); b <= bins.bin(y1); ++b)
    for (unsigned q = bins.first[std::size_t(b)]; q < bins.first[std::size_t(b) + 1]; ++q) {
      const Point& p = v[bins.edges[q]];
      const Point& r = v[(bins.edges[q] + 1) % n];
      double enter = 0.0, leave = 1.0;
      const double lower[2] = {x0, y0}, upper[2] = {x1, y1};
      for (int a = 0; a < 2 && enter < leave; ++a) {
        const double d = r[a] - p[a];
        if (d == 0.0) {
          if (!(p[a] > lower[a] && p[a] < upper[a])) leave = enter;  // along the slab's side or outside it
          continue;
        }
        const double t0 = (lower[a] - p[a]) / d, t1 = (upper[a] - p[a]) / d;
        enter = std::max(enter, std::min(t0, t1));
        leave = std::min(leave, std::max(t0, t1));
      }
      if (enter < leave) return true;
    }
  return false;
}

bool ShapeUnion::may_pass_between_probes(double x0, double x1, double y0, double y1) const {
  for (std::size_t k = 0; k < shapes_.size(); ++k) {
    const auto& [lo, hi] = boxes_[k];
    if (!(lo[0] < x1 && hi[0] > x0 && lo[1] < y1 && hi[1] > y0)) continue;
    if (std::holds_alternative<Polygon>(shapes_[k]) ? polygon_edge_through(k, x0, x1, y0, y1)
                                                     : hi[0] - lo[0] < x1 - x0 || hi[1] - lo[1] < y1 - y0)
      return true;
    // A ring's band narrower than the cell (it may pass between the probes), or its hole narrower or
    // lower than the cell and reaching into it, as a small circle would.
    if (const auto* r = std::get_if<Ring>(&shapes_[k])) {
      const double band = r->outer_radius - r->inner_radius;
      const double d = 2.0 * r->inner_radius, cx = r->centre[0], cy = r->centre[1];
      if (band < x1 - x0 || band < y1 - y0 ||
          ((d < x1 - x0 || d < y1 - y0) && cx - 0.5 * d < x1 && cx + 0.5 * d > x0 && cy - 0.5 * d < y1 &&
           cy + 0.5 * d > y0))
        return true;
    }
  }
  return false;
}

double ShapeUnion::fraction(double x0, double x1, double y0, double y1, bool axisymmetric, int samples) const {
  // Fast path: the four corners and the centre agree (cells are small against the shapes), unless an
  // outline may pass between them.
  const bool small_shape_here = may_pass_between_probes(x0, x1, y0, y1);
  const int probe = contains(x0, y0) + contains(x1, y0) + contains(x0, y1) + contains(x1, y1) +
                    contains(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  if (probe == 0 && !small_shape_here) return 0.0;
  if (probe == 5 && !small_shape_here) return 1.0;
  double inside = 0.0, all = 0.0;
  for (int a = 0; a < samples; ++a) {
    const double x = x0 + (a + 0.5) * (x1 - x0) / samples;
    const double weight = axisymmetric ? x : 1.0;
    for (int b = 0; b < samples; ++b) {
      const double y = y0 + (b + 0.5) * (y1 - y0) / samples;
      inside += weight * contains(x, y);
      all += weight;
    }
  }
  return inside / all;
}

}  // namespace granflow::interface

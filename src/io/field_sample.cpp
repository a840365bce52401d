#include "io/field_sample.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace granflow {

SideRules velocity_side_rules(const BoundarySet& boundaries, int axis, int dimension) {
  SideRules rules;
  for (Side s : sides_of_dimension(dimension)) {
    const BoundaryCondition& bc = boundary(boundaries, s);
    SideRule& r = rules[static_cast<int>(s)];
    const bool normal = normal_axis(s) == axis;
    switch (bc.kind) {
      case BoundaryKind::wall:  // its normal component is zero
      case BoundaryKind::inlet: r = {SideRule::Kind::value, bc.velocity[axis], bc.inflow_span}; break;
      case BoundaryKind::slip: r = normal ? SideRule{SideRule::Kind::value, 0.0} : SideRule{}; break;
      case BoundaryKind::atmosphere: r = SideRule{}; break;
      case BoundaryKind::periodic: r = SideRule{}; break;  // unread: sample_field takes the join's mean
    }
  }
  return rules;
}

SideRules pressure_side_rules() {
  SideRules rules;
  for (auto& r : rules) r.kind = SideRule::Kind::linear;
  return rules;
}

namespace {
// The value on a side from the rule and the two cells nearest to it along the normal: `next` at
// distance d1 from the side, `second` d2 beyond it (d2 = 0 if there is no second cell).
double side_value(const SideRule& r, double next, double second, double d1, double d2) {
  switch (r.kind) {
    case SideRule::Kind::value: return r.value;
    case SideRule::Kind::zero_gradient: return next;
    case SideRule::Kind::linear: return d2 > 0.0 ? next + (next - second) * d1 / d2 : next;
  }
  return next;
}

// The sample nodes along one axis are the low side, the n cell centres and the high side (node k is
// cell k - 1). Returns the node at or below x (in [0, n]) and the weight of the next one.
void bracket(int n, double lower, double upper, double x, auto centre, int& k0, double& w) {
  const auto node = [&](int k) { return k == 0 ? lower : k == n + 1 ? upper : centre(k - 1); };
  x = std::clamp(x, lower, upper);
  int lo = 0, hi = n + 1;  // node(lo) <= x <= node(hi)
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (node(mid) <= x ? lo : hi) = mid;
  }
  k0 = lo;
  const double span = node(lo + 1) - node(lo);
  w = span > 0.0 ? (x - node(lo)) / span : 0.0;
}
}  // namespace

double sample_field(const Grid& g, const std::vector<double>& values, const SideRules& sides, double x, double y,
                    double z) {
  const int nx = g.nx(), ny = g.ny(), nz = g.dimension() == 3 ? g.nz() : 1;
  int a, b, c = 0;
  double wx, wy, wz = 0.0;
  bracket(nx, g.spec().lower[0], g.spec().upper[0], x, [&](int i) { return g.xc(i); }, a, wx);
  bracket(ny, g.spec().lower[1], g.spec().upper[1], y, [&](int j) { return g.yc(j); }, b, wy);
  if (nz > 1) bracket(nz, g.spec().lower[2], g.spec().upper[2], z, [&](int k) { return g.zc(k); }, c, wz);
  // The rule of side s at the face of the cell i, j, k on it (a value held over a span: its share there).
  const auto rule = [&](Side s, int i, int j, int k) {
    SideRule r = sides[static_cast<int>(s)];
    if (r.kind == SideRule::Kind::value) r.value *= span_share(r.span, g, s, i, j, k);
    return r;
  };
  const auto cell = [&](int i, int j, int k) { return values[(size_t(k) * ny + j) * nx + i]; };
  // Value at node column i (-1 = west side, nx = east side), cell row j and layer k; on a periodic
  // strip both are the join, between the end columns.
  const auto in_row = [&](int i, int j, int k) {
    if ((i == -1 || i == nx) && g.periodic_x()) {
      const double west = 0.5 * g.dx(0), east = 0.5 * g.dx(nx - 1);  // the join's distances to their centres
      return (cell(0, j, k) * east + cell(nx - 1, j, k) * west) / (west + east);
    }
    if (i == -1)
      return side_value(rule(Side::west, i, j, k), cell(0, j, k), nx > 1 ? cell(1, j, k) : 0.0, 0.5 * g.dx(0),
                        nx > 1 ? g.xc(1) - g.xc(0) : 0.0);
    if (i == nx)
      return side_value(rule(Side::east, i, j, k), cell(nx - 1, j, k), nx > 1 ? cell(nx - 2, j, k) : 0.0,
                        0.5 * g.dx(nx - 1), nx > 1 ? g.xc(nx - 1) - g.xc(nx - 2) : 0.0);
    return cell(i, j, k);
  };
  // ... at node (i, j) of layer k, j = -1 the south side, ny the north side. A corner takes the rule
  // of the south or north side applied to the values of its column (the west or east side's).
  const auto in_layer = [&](int i, int j, int k) {
    if (j == -1)
      return side_value(rule(Side::south, i, j, k), in_row(i, 0, k), ny > 1 ? in_row(i, 1, k) : 0.0, 0.5 * g.dy(0),
                        ny > 1 ? g.yc(1) - g.yc(0) : 0.0);
    if (j == ny)
      return side_value(rule(Side::north, i, j, k), in_row(i, ny - 1, k), ny > 1 ? in_row(i, ny - 2, k) : 0.0,
                        0.5 * g.dy(ny - 1), ny > 1 ? g.yc(ny - 1) - g.yc(ny - 2) : 0.0);
    return in_row(i, j, k);
  };
  // ... at node (i, j, k), k = -1 the front side, nz the back side (a mesh of layers only), by the
  // front's or back's rule on the values of the layers next to it.
  const auto node = [&](int i, int j, int k) {
    if (k == -1)
      return side_value(rule(Side::front, i, j, k), in_layer(i, j, 0), nz > 1 ? in_layer(i, j, 1) : 0.0, 0.5 * g.dz(0),
                        nz > 1 ? g.zc(1) - g.zc(0) : 0.0);
    if (k == nz)
      return side_value(rule(Side::back, i, j, k), in_layer(i, j, nz - 1), nz > 1 ? in_layer(i, j, nz - 2) : 0.0,
                        0.5 * g.dz(nz - 1), nz > 1 ? g.zc(nz - 1) - g.zc(nz - 2) : 0.0);
    return in_layer(i, j, k);
  };
  const int i0 = a - 1, j0 = b - 1;  // node index n is cell n - 1
  const auto bilinear = [&](int k) {
    return (1 - wy) * ((1 - wx) * node(i0, j0, k) + wx * node(i0 + 1, j0, k)) +
           wy * ((1 - wx) * node(i0, j0 + 1, k) + wx * node(i0 + 1, j0 + 1, k));
  };
  if (nz == 1) return bilinear(0);
  const int k0 = c - 1;
  return (1 - wz) * bilinear(k0) + wz * bilinear(k0 + 1);
}

void fill_obstacle_walls(const Grid& g, const std::vector<double>& blocked, const SideRule& wall,
                         std::vector<double>& values) {
  const int nx = g.nx(), ny = g.ny(), nz = g.dimension() == 3 ? g.nz() : 1;
  using Step = std::array<int, 3>;
  // Along a periodic x a neighbour's column runs on through the join.
  const bool periodic = g.periodic_x();
  const auto column = [&](int i) { return periodic ? (i + nx) % nx : i; };
  const auto at = [&](int i, int j, int k) { return (size_t(k) * ny + j) * nx + size_t(column(i)); };
  const auto open = [&](int i, int j, int k) {
    return column(i) >= 0 && column(i) < nx && j >= 0 && j < ny && k >= 0 && k < nz && blocked[at(i, j, k)] <= 0.5;
  };
  const std::vector<double> before = values;  // read open cells only, as they were
  std::vector<char> filled(values.size(), 0);
  // A blocked cell beside an open one: the line through the open cell's value and the wall's,
  // continued to the blocked cell's centre.
  std::vector<Step> faces{{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}};
  if (nz > 1) faces.insert(faces.end(), {Step{0, 0, 1}, Step{0, 0, -1}});
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (open(i, j, k)) continue;
        for (const auto [di, dj, dk] : faces) {
          const int io = i + di, jo = j + dj, ko = k + dk;  // the open cell in front of the wall
          if (!open(io, jo, ko)) continue;
          const int axis = di != 0 ? 0 : dj != 0 ? 1 : 2;
          const int n_open = axis == 0 ? column(io) : axis == 1 ? jo : ko, n_blocked = axis == 0 ? i : axis == 1 ? j : k;
          const int step = di + dj + dk, n_second = axis == 0 ? column(io + di) : n_open + step;
          const bool second = open(io + di, jo + dj, ko + dk);
          const double d1 = 0.5 * g.width(axis, n_open), d_blocked = 0.5 * g.width(axis, n_blocked);
          // The centres' distance; across a periodic join, half of each width.
          const double d2 = !second                      ? 0.0
                            : n_second == n_open + step ? std::abs(g.centre(axis, n_second) - g.centre(axis, n_open))
                                                        : 0.5 * (g.width(axis, n_open) + g.width(axis, n_second));
          const double next = before[at(io, jo, ko)];
          const double on_wall = side_value(wall, next, second ? before[at(io + di, jo + dj, ko + dk)] : 0.0, d1, d2);
          values[at(i, j, k)] = next + (on_wall - next) * (d1 + d_blocked) / d1;
          filled[at(i, j, k)] = 1;
          break;
        }
      }
  // A blocked cell diagonal to an open one across an edge the obstacles make (both cells beside them
  // blocked, filled above): the open cell's value mirrored across both walls, X + Y - O, which keeps a
  // linear field linear and, for a wall's value, is O itself mirrored twice.
  std::vector<Step> edges{{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
  if (nz > 1)
    for (int s = 0; s < 4; ++s) {
      const int d1 = s % 2 ? -1 : 1, d2 = s / 2 ? -1 : 1;
      edges.insert(edges.end(), {Step{d1, 0, d2}, Step{0, d1, d2}});
    }
  std::vector<char> by_edge(values.size(), 0);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (open(i, j, k) || filled[at(i, j, k)]) continue;
        for (const auto [di, dj, dk] : edges) {
          // The two cells between: one step along each of the edge's two axes.
          const Step first = di != 0 ? Step{di, 0, 0} : Step{0, dj, 0};
          const Step other{di - first[0], dj - first[1], dk - first[2]};
          const size_t a = at(i + first[0], j + first[1], k + first[2]);
          const size_t b = at(i + other[0], j + other[1], k + other[2]);
          if (!open(i + di, j + dj, k + dk) || !filled[a] || !filled[b]) continue;
          const double o = before[at(i + di, j + dj, k + dk)];
          values[at(i, j, k)] = wall.kind == SideRule::Kind::value ? o : values[b] + values[a] - o;
          by_edge[at(i, j, k)] = 1;
          break;
        }
      }
  if (nz == 1) return;
  // On a mesh of layers, a blocked cell diagonal to an open one across a corner three walls make: the
  // open cell's value mirrored across all three, X + Y + Z - 2 O from its mirrors across one wall each
  // (the blocked cells beside it, filled above), and 2 v - O for a wall's value v.
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (open(i, j, k) || filled[at(i, j, k)] || by_edge[at(i, j, k)]) continue;
        for (int s = 0; s < 8; ++s) {
          const int di = s & 1 ? -1 : 1, dj = s & 2 ? -1 : 1, dk = s & 4 ? -1 : 1;
          const size_t x = at(i, j + dj, k + dk), y = at(i + di, j, k + dk), z = at(i + di, j + dj, k);
          if (!open(i + di, j + dj, k + dk) || !filled[x] || !filled[y] || !filled[z]) continue;
          const double o = before[at(i + di, j + dj, k + dk)];
          values[at(i, j, k)] =
              wall.kind == SideRule::Kind::value ? 2.0 * wall.value - o : values[x] + values[y] + values[z] - 2.0 * o;
          break;
        }
      }
}

}  // namespace granflow

#include "io/field_sample.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace granflow {

SideRules velocity_side_rules(const BoundarySet& boundaries, int axis) {
  SideRules rules;
  for (Side s : planar_sides) {
    const BoundaryCondition& bc = boundary(boundaries, s);
    SideRule& r = rules[static_cast<int>(s)];
    const bool normal = normal_axis(s) == axis;
    switch (bc.kind) {
      case BoundaryKind::wall: r = {SideRule::Kind::value, normal ? 0.0 : bc.wall_velocity[axis]}; break;
      case BoundaryKind::slip: r = normal ? SideRule{SideRule::Kind::value, 0.0} : SideRule{}; break;
      case BoundaryKind::atmosphere: r = SideRule{}; break;
      case BoundaryKind::periodic: r = SideRule{}; break;  // the nearest cell's (the ends are neighbours)
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

double sample_field(const Grid& g, const std::vector<double>& values, const SideRules& sides, double x, double y) {
  const int nx = g.nx(), ny = g.ny();
  int a, b;
  double wx, wy;
  bracket(nx, g.spec().lower[0], g.spec().upper[0], x, [&](int i) { return g.xc(i); }, a, wx);
  bracket(ny, g.spec().lower[1], g.spec().upper[1], y, [&](int j) { return g.yc(j); }, b, wy);
  const auto rule = [&](Side s) -> const SideRule& { return sides[static_cast<int>(s)]; };
  const auto cell = [&](int i, int j) { return values[size_t(j) * nx + i]; };
  // Value at node column i (-1 = west side, nx = east side) and cell row j.
  const auto in_row = [&](int i, int j) {
    if (i == -1) return side_value(rule(Side::west), cell(0, j), nx > 1 ? cell(1, j) : 0.0, 0.5 * g.dx(0),
                                   nx > 1 ? g.xc(1) - g.xc(0) : 0.0);
    if (i == nx) return side_value(rule(Side::east), cell(nx - 1, j), nx > 1 ? cell(nx - 2, j) : 0.0,
                                   0.5 * g.dx(nx - 1), nx > 1 ? g.xc(nx - 1) - g.xc(nx - 2) : 0.0);
    return cell(i, j);
  };
  // Value at node (i, j), j = -1 the south side, ny the north side. A corner takes the rule of the
  // south or north side applied to the values of its column (the west or east side's).
  const auto node = [&](int i, int j) {
    if (j == -1) return side_value(rule(Side::south), in_row(i, 0), ny > 1 ? in_row(i, 1) : 0.0, 0.5 * g.dy(0),
                                   ny > 1 ? g.yc(1) - g.yc(0) : 0.0);
    if (j == ny) return side_value(rule(Side::north), in_row(i, ny - 1), ny > 1 ? in_row(i, ny - 2) : 0.0,
                                   0.5 * g.dy(ny - 1), ny > 1 ? g.yc(ny - 1) - g.yc(ny - 2) : 0.0);
    return in_row(i, j);
  };
  const int i0 = a - 1, j0 = b - 1;  // node index k is cell k - 1
  return (1 - wy) * ((1 - wx) * node(i0, j0) + wx * node(i0 + 1, j0)) +
         wy * ((1 - wx) * node(i0, j0 + 1) + wx * node(i0 + 1, j0 + 1));
}

void fill_obstacle_walls(const Grid& g, const std::vector<double>& blocked, const SideRule& wall,
                         std::vector<double>& values) {
  const int nx = g.nx(), ny = g.ny();
  const auto at = [&](int i, int j) { return size_t(j) * nx + i; };
  const auto open = [&](int i, int j) { return i >= 0 && i < nx && j >= 0 && j < ny && blocked[at(i, j)] <= 0.5; };
  const std::vector<double> before = values;  // read open cells only, as they were
  std::vector<char> filled(values.size(), 0);
  // A blocked cell beside an open one: the line through the open cell's value and the wall's,
  // continued to the blocked cell's centre.
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (open(i, j)) continue;
      for (const auto [di, dj] : {std::array{0, 1}, std::array{0, -1}, std::array{1, 0}, std::array{-1, 0}}) {
        const int io = i + di, jo = j + dj;  // the open cell in front of the wall
        if (!open(io, jo)) continue;
        const bool second = open(io + di, jo + dj);
        const double d1 = di != 0 ? 0.5 * g.dx(io) : 0.5 * g.dy(jo);
        const double d_blocked = di != 0 ? 0.5 * g.dx(i) : 0.5 * g.dy(j);
        const double d2 = !second ? 0.0 : di != 0 ? std::abs(g.xc(io + di) - g.xc(io)) : std::abs(g.yc(jo + dj) - g.yc(jo));
        const double next = before[at(io, jo)];
        const double on_wall = side_value(wall, next, second ? before[at(io + di, jo + dj)] : 0.0, d1, d2);
        values[at(i, j)] = next + (on_wall - next) * (d1 + d_blocked) / d1;
        filled[at(i, j)] = 1;
        break;
      }
    }
  // A blocked cell diagonal to an open one in a corner the obstacles make (both cells beside them
  // blocked, filled above): the open cell's value mirrored across both walls, X + Y - O, which keeps a
  // linear field linear and, for a wall's value, is O itself mirrored twice.
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (open(i, j) || filled[at(i, j)]) continue;
      for (const auto [di, dj] : {std::array{1, 1}, std::array{-1, 1}, std::array{1, -1}, std::array{-1, -1}}) {
        if (!open(i + di, j + dj) || !filled[at(i + di, j)] || !filled[at(i, j + dj)]) continue;
        const double o = before[at(i + di, j + dj)], x = values[at(i, j + dj)], y = values[at(i + di, j)];
        values[at(i, j)] = wall.kind == SideRule::Kind::value ? o : x + y - o;
        break;
      }
    }
}

}  // namespace granflow

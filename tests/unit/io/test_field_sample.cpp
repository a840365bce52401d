// Point samples of a cell field: bilinear between centres, and between the last centre and a side
// towards the side's value from its rule (a boundary value, a zero gradient, or the last two cells'
// line continued).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "io/field_sample.hpp"
#include "mesh/grid.hpp"

namespace granflow {
namespace {

GridSpec graded_spec() {
  GridSpec spec;
  spec.cells = {7, 5, 1};
  spec.lower = {-0.3, 0.1};
  spec.upper = {0.9, 0.6};
  spec.grading = {2.0, 0.5};
  return spec;
}

template <class F>
std::vector<double> cell_values(const Grid& g, F f) {
  std::vector<double> v(size_t(g.nx()) * g.ny());
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) v[size_t(j) * g.nx() + i] = f(g.xc(i), g.yc(j));
  return v;
}

// Points over the whole domain, its sides and corners included.
std::vector<std::array<double, 2>> points(const GridSpec& s) {
  std::vector<std::array<double, 2>> p;
  const int n = 23;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
      p.push_back({s.lower[0] + (s.upper[0] - s.lower[0]) * a / n, s.lower[1] + (s.upper[1] - s.lower[1]) * b / n});
  return p;
}

TEST(FieldSample, LinearRuleReproducesALinearFieldUpToTheSidesAndCorners) {
  const Grid g(PETSC_COMM_SELF, graded_spec());
  const auto f = [](double x, double y) { return 2.0 + 3.0 * x - 5.0 * y; };
  const auto values = cell_values(g, f);
  for (const auto& [x, y] : points(g.spec()))
    EXPECT_NEAR(sample_field(g, values, pressure_side_rules(), x, y), f(x, y), 1e-12) << x << ", " << y;
}

TEST(FieldSample, WallsGiveTheirVelocitySlipSidesNoNormalFlowAtmospheresAZeroGradient) {
  const Grid g(PETSC_COMM_SELF, graded_spec());
  BoundarySet b;
  b[int(Side::west)].kind = BoundaryKind::slip;
  b[int(Side::east)].kind = BoundaryKind::atmosphere;
  b[int(Side::south)].kind = BoundaryKind::wall;
  b[int(Side::north)].kind = BoundaryKind::wall;
  b[int(Side::north)].velocity = {1.5, 0.0};
  const auto f = [](double x, double y) { return 0.7 + x * x + y; };
  const auto values = cell_values(g, f);
  const SideRules u_sides = velocity_side_rules(b, 0, 2), v_sides = velocity_side_rules(b, 1, 2);
  const int nx = g.nx(), ny = g.ny();
  const double x_mid = g.xc(3), y_mid = g.yc(2);
  const double top = g.spec().upper[1], bottom = g.spec().lower[1];
  const double left = g.spec().lower[0], right = g.spec().upper[0];
  // On the lid: its tangential velocity, and no normal one; halfway to it, the mean of both.
  EXPECT_DOUBLE_EQ(sample_field(g, values, u_sides, x_mid, top), 1.5);
  EXPECT_DOUBLE_EQ(sample_field(g, values, v_sides, x_mid, top), 0.0);
  const double y_half = 0.5 * (g.yc(ny - 1) + top);
  EXPECT_NEAR(sample_field(g, values, u_sides, x_mid, y_half), 0.5 * (f(x_mid, g.yc(ny - 1)) + 1.5), 1e-12);
  // On the floor: at rest.
  EXPECT_DOUBLE_EQ(sample_field(g, values, u_sides, x_mid, bottom), 0.0);
  EXPECT_DOUBLE_EQ(sample_field(g, values, v_sides, x_mid, bottom), 0.0);
  // On the slip side: no normal velocity, the tangential one of the next cell.
  EXPECT_DOUBLE_EQ(sample_field(g, values, u_sides, left, y_mid), 0.0);
  EXPECT_NEAR(sample_field(g, values, v_sides, left, y_mid), f(g.xc(0), y_mid), 1e-12);
  // At the atmosphere: both components those of the next cell.
  EXPECT_NEAR(sample_field(g, values, u_sides, right, y_mid), f(g.xc(nx - 1), y_mid), 1e-12);
  EXPECT_NEAR(sample_field(g, values, v_sides, right, y_mid), f(g.xc(nx - 1), y_mid), 1e-12);
  // Between centres the sample is bilinear whatever the rules.
  const double xq = 0.25 * g.xc(2) + 0.75 * g.xc(3), yq = 0.6 * g.yc(1) + 0.4 * g.yc(2);
  const double expected = 0.6 * (0.25 * f(g.xc(2), g.yc(1)) + 0.75 * f(g.xc(3), g.yc(1))) +
                          0.4 * (0.25 * f(g.xc(2), g.yc(2)) + 0.75 * f(g.xc(3), g.yc(2)));
  EXPECT_NEAR(sample_field(g, values, u_sides, xq, yq), expected, 1e-12);
  // Outside the domain: the nearest point of it.
  EXPECT_DOUBLE_EQ(sample_field(g, values, u_sides, x_mid, top + 1.0), 1.5);
}

TEST(FieldSample, OneCellAcrossFallsBackToItsValue) {
  GridSpec spec;
  spec.cells = {1, 1, 1};
  const Grid g(PETSC_COMM_SELF, spec);
  const std::vector<double> values{4.25};
  for (const auto& [x, y] : points(spec)) EXPECT_DOUBLE_EQ(sample_field(g, values, pressure_side_rules(), x, y), 4.25);
}

// Within half a cell of an obstacle a sample runs to the wall's value, as near a side of the domain:
// a barrier of blocked cells (columns 4-6, rows 0-2 of 7 x 5 graded cells) with a linear pressure,
// a velocity and a scalar in the open cells. Before, the samples blended in whatever the blocked
// cells held (their start-up values).
TEST(FieldSample, ObstacleWallsGiveTheirValueAsTheSidesDo) {
  const Grid g(PETSC_COMM_SELF, graded_spec());
  std::vector<double> blocked(size_t(g.nx()) * g.ny(), 0.0);
  for (int j = 0; j <= 2; ++j)
    for (int i = 4; i <= 6; ++i) blocked[size_t(j) * g.nx() + i] = 1.0;
  const auto pressure = [](double x, double y) { return 2.0 + 3.0 * x - 5.0 * y; };
  auto p = cell_values(g, pressure), u = cell_values(g, [](double, double) { return 0.8; }),
       c = cell_values(g, [](double x, double) { return 0.3 + x; });
  for (size_t k = 0; k < blocked.size(); ++k)
    if (blocked[k] > 0.5) p[k] = u[k] = c[k] = 1e3;  // stale values the samples must not read
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::linear, 0.0}, p);
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::value, 0.0}, u);
  fill_obstacle_walls(g, blocked, SideRule{}, c);
  const double west_face = g.xc(4) - 0.5 * g.dx(4), top_face = g.yc(2) + 0.5 * g.dy(2);
  const double y_beside = g.yc(1), x_above = g.xc(5);
  // On the barrier's west face, beside it, and on its top, above it.
  EXPECT_NEAR(sample_field(g, p, pressure_side_rules(), west_face, y_beside), pressure(west_face, y_beside), 1e-12);
  EXPECT_NEAR(sample_field(g, p, pressure_side_rules(), x_above, top_face), pressure(x_above, top_face), 1e-12);
  EXPECT_NEAR(sample_field(g, u, SideRules{}, west_face, y_beside), 0.0, 1e-12);
  EXPECT_NEAR(sample_field(g, u, SideRules{}, x_above, top_face), 0.0, 1e-12);
  EXPECT_NEAR(sample_field(g, c, SideRules{}, west_face, y_beside), 0.3 + g.xc(3), 1e-12);
  // Half way from the open centre to the wall: half way between their values.
  const double x_half = 0.5 * (g.xc(3) + west_face);
  EXPECT_NEAR(sample_field(g, u, SideRules{}, x_half, y_beside), 0.4, 1e-12);
}

// In a corner the obstacles make (a wall and a floor slab meeting, the open cell (4, 2) between them),
// the blocked cell diagonal to the open one has no open neighbour of its own, yet a sample near the
// corner reads it: it takes the open cell's value mirrored across both walls.
TEST(FieldSample, ObstacleCornersGiveTheWallsValue) {
  GridSpec spec;
  spec.cells = {8, 6, 1};
  spec.upper = {0.8, 0.6};
  const Grid g(PETSC_COMM_SELF, spec);
  std::vector<double> blocked(48, 0.0);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 8; ++i) blocked[size_t(j) * 8 + i] = i >= 5 || j <= 1 ? 1.0 : 0.0;
  const auto pressure = [](double x, double y) { return 2.0 + 3.0 * x - 5.0 * y; };
  auto p = cell_values(g, pressure), u = cell_values(g, [](double, double) { return 0.8; });
  for (size_t k = 0; k < blocked.size(); ++k)
    if (blocked[k] > 0.5) p[k] = u[k] = 1e3;
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::linear, 0.0}, p);
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::value, 0.0}, u);
  const double corner_x = 0.5, corner_y = 0.2;  // where the wall x = 0.5 meets the slab's top y = 0.2
  for (const auto& [x, y] : {std::array{corner_x, corner_y}, std::array{corner_x - 0.02, corner_y + 0.01},
                             std::array{corner_x - 0.01, corner_y + 0.03}}) {
    EXPECT_NEAR(sample_field(g, p, pressure_side_rules(), x, y), pressure(x, y), 1e-12) << x << ", " << y;
    if (x == corner_x) EXPECT_NEAR(sample_field(g, u, SideRules{}, x, y), 0.0, 1e-12);
    EXPECT_LT(std::abs(sample_field(g, u, SideRules{}, x, y)), 0.8) << x << ", " << y;
  }
}

// A periodic strip has no west or east side: a sample there is the join's, the mean of the two end
// columns, the same at both ends, and between the join and the first centre it is linear. A wall of
// blocked cells in the last column faces the first column across the join: its face, the join, has
// the wall's velocity.
TEST(FieldSample, APeriodicStripSamplesAcrossItsJoin) {
  GridSpec spec;
  spec.cells = {8, 4, 1};
  spec.upper = {0.8, 0.4};
  spec.periodic_x = true;
  const Grid g(PETSC_COMM_SELF, spec);
  const auto f = [](double x, double y) { return std::cos(2.0 * std::acos(-1.0) * x / 0.8) + 3.0 * y; };
  const auto v = cell_values(g, f);
  const SideRules walls{SideRule{SideRule::Kind::value, 7.0}, SideRule{SideRule::Kind::value, 7.0}};  // unread
  for (const double y : {0.15, 0.25}) {
    const double join = 0.5 * (f(0.05, y) + f(0.75, y));
    EXPECT_NEAR(sample_field(g, v, walls, 0.0, y), join, 1e-14) << y;
    EXPECT_NEAR(sample_field(g, v, walls, 0.8, y), join, 1e-14) << y;
    EXPECT_NEAR(sample_field(g, v, walls, 0.02, y), 0.6 * join + 0.4 * f(0.05, y), 1e-14) << y;
    EXPECT_NEAR(sample_field(g, v, walls, 0.79, y), 0.8 * join + 0.2 * f(0.75, y), 1e-14) << y;
  }
  // A wall two columns thick at the east end (columns 6 and 7): column 7 faces column 0 across the join.
  std::vector<double> blocked(32, 0.0), u(32, 0.8);
  for (int j = 0; j < 4; ++j)
    for (int i = 6; i < 8; ++i) {
      blocked[size_t(j) * 8 + i] = 1.0;
      u[size_t(j) * 8 + i] = 1e3;  // stale values the samples must not read
    }
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::value, 0.0}, u);
  EXPECT_NEAR(u[7], -0.8, 1e-14);  // column 0's velocity mirrored across the wall's face at the join
  EXPECT_NEAR(u[6], -0.8, 1e-14);  // column 5's across the wall's west face
  for (const double x : {0.0, 0.8}) EXPECT_NEAR(sample_field(g, u, SideRules{}, x, 0.15), 0.0, 1e-14) << x;
  EXPECT_NEAR(sample_field(g, u, SideRules{}, 0.025, 0.15), 0.4, 1e-14);  // halfway to the first centre
}

// On a mesh of layers: graded along all three axes, cells 5 x 4 x 3.
GridSpec layered_spec() {
  GridSpec spec;
  spec.cells = {5, 4, 3};
  spec.lower = {-0.3, 0.1, -0.2};
  spec.upper = {0.9, 0.6, 0.4};
  spec.grading = {2.0, 0.5, 1.5};
  return spec;
}

template <class F>
std::vector<double> layered_values(const Grid& g, F f) {
  std::vector<double> v(size_t(g.nx()) * g.ny() * g.nz());
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) v[(size_t(k) * g.ny() + j) * g.nx() + i] = f(g.xc(i), g.yc(j), g.zc(k));
  return v;
}

// A linear field is trilinear: sampled exactly between the centres, and by the pressure's rule (the
// last two cells' line continued) up to every side, edge and corner of the box.
TEST(FieldSample, ALayeredMeshSamplesALinearFieldExactlyUpToItsSidesEdgesAndCorners) {
  const Grid g(PETSC_COMM_SELF, layered_spec());
  ASSERT_EQ(g.dimension(), 3);
  const auto f = [](double x, double y, double z) { return 2.0 + 3.0 * x - 5.0 * y + 7.0 * z; };
  const auto values = layered_values(g, f);
  const auto& s = g.spec();
  const int n = 9;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
      for (int c = 0; c <= n; ++c) {
        const double x = s.lower[0] + (s.upper[0] - s.lower[0]) * a / n, y = s.lower[1] + (s.upper[1] - s.lower[1]) * b / n,
                     z = s.lower[2] + (s.upper[2] - s.lower[2]) * c / n;
        EXPECT_NEAR(sample_field(g, values, pressure_side_rules(), x, y, z), f(x, y, z), 1e-12) << x << ", " << y << ", " << z;
      }
  // Outside the box: its nearest point.
  EXPECT_NEAR(sample_field(g, values, pressure_side_rules(), 0.2, 0.3, 9.0), f(0.2, 0.3, 0.4), 1e-12);
}

// The front and back sides' rules: a wall's velocity on the front, no normal velocity and the next
// cell's tangential one on a slip back side.
TEST(FieldSample, TheFrontAndBackGiveTheirVelocityAsTheOtherSidesDo) {
  const Grid g(PETSC_COMM_SELF, layered_spec());
  BoundarySet b;
  b[int(Side::front)].kind = BoundaryKind::wall;
  b[int(Side::front)].velocity = {0.5, 0.0, 0.0};
  b[int(Side::back)].kind = BoundaryKind::slip;
  const auto f = [](double x, double y, double z) { return 0.7 + x * x + y - z; };
  const auto values = layered_values(g, f);
  const SideRules u = velocity_side_rules(b, 0, 3), w = velocity_side_rules(b, 2, 3);
  const double x = g.xc(2), y = g.yc(1), front = g.spec().lower[2], back = g.spec().upper[2];
  EXPECT_DOUBLE_EQ(sample_field(g, values, u, x, y, front), 0.5);
  EXPECT_DOUBLE_EQ(sample_field(g, values, w, x, y, front), 0.0);
  EXPECT_NEAR(sample_field(g, values, u, x, y, 0.5 * (front + g.zc(0))), 0.5 * (0.5 + f(x, y, g.zc(0))), 1e-12);
  EXPECT_DOUBLE_EQ(sample_field(g, values, w, x, y, back), 0.0);
  EXPECT_NEAR(sample_field(g, values, u, x, y, back), f(x, y, g.zc(g.nz() - 1)), 1e-12);
  // A planar mesh's rules leave the front and back at their defaults.
  EXPECT_EQ(velocity_side_rules(b, 0, 2)[int(Side::front)].kind, SideRule::Kind::zero_gradient);
}

// Obstacles of layers: a floor slab (rows 0-1), a wall (columns 4-5) and a front slab (layer 0) meet
// in a corner of three walls at (0.4, 0.2, 0.1) on cells of 0.1 m; the blocked cells beside the open
// ones, across the edges and across the corner take the walls' values, so that a linear pressure is
// sampled exactly up to the corner and a static wall's velocity is 0 on it.
TEST(FieldSample, ObstacleCornersOfThreeWallsGiveTheWallsValue) {
  GridSpec spec;
  spec.cells = {6, 5, 4};
  spec.upper = {0.6, 0.5, 0.4};
  const Grid g(PETSC_COMM_SELF, spec);
  std::vector<double> blocked(120, 0.0);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) blocked[(size_t(k) * 5 + j) * 6 + i] = i >= 4 || j <= 1 || k == 0 ? 1.0 : 0.0;
  const auto pressure = [](double x, double y, double z) { return 2.0 + 3.0 * x - 5.0 * y + 4.0 * z; };
  auto p = layered_values(g, pressure), u = layered_values(g, [](double, double, double) { return 0.8; });
  for (size_t n = 0; n < blocked.size(); ++n)
    if (blocked[n] > 0.5) p[n] = u[n] = 1e3;  // stale values the samples must not read
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::linear, 0.0}, p);
  fill_obstacle_walls(g, blocked, SideRule{SideRule::Kind::value, 0.0}, u);
  // The cell across the corner from the open cell (3, 2, 1): the open cell mirrored across all three.
  EXPECT_NEAR(p[(size_t(0) * 5 + 1) * 6 + 4], pressure(0.45, 0.15, 0.05), 1e-12);
  EXPECT_NEAR(u[(size_t(0) * 5 + 1) * 6 + 4], -0.8, 1e-12);
  const double cx = 0.4, cy = 0.2, cz = 0.1;
  for (const auto& [x, y, z] : {std::array{cx, cy, cz}, std::array{cx - 0.02, cy + 0.01, cz + 0.03},
                                std::array{cx - 0.04, cy + 0.03, cz + 0.01}, std::array{cx, cy + 0.02, cz + 0.02}}) {
    EXPECT_NEAR(sample_field(g, p, pressure_side_rules(), x, y, z), pressure(x, y, z), 1e-12) << x << ", " << y << ", " << z;
    EXPECT_LT(std::abs(sample_field(g, u, SideRules{}, x, y, z)), 0.8) << x << ", " << y << ", " << z;
  }
  EXPECT_NEAR(sample_field(g, u, SideRules{}, cx, cy, cz), 0.0, 1e-12);
}

}  // namespace
}  // namespace granflow

// Obstacles and terrain on a mesh of layers ([[obstacle]] solids, mesh/obstacles.hpp): a face between
// an open and a blocked cell is a static no-slip wall, as the domain's own six sides are.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "layer_on_terrain.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

struct Collapse3d {
  std::vector<double> c, u, v, w;
  std::array<std::array<double, 3>, 6> sides{};
  std::array<double, 3> obstacle{};
  double kinetic = 0.0, volume_error = 0.0;
  int nx = 0, ny = 0, nz = 0;
};

// The collapse of cases/bui2008_experiment.toml turned into a block 10 x 5 x 3 cm against the west
// wall, the floor and the front wall of a box 30 x 10 x 6 cm (1 cm cells) closed but for its top and
// its east side: the soil spreads along x and z, so the flow is three-dimensional at every wall.
Collapse3d collapse_3d(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(),
                   {"output.progress_seconds=0", "time.end=0.2", "output.interval=0.2", "physics.gravity=[0,-9.81,0]",
                    "mesh.upper=[0.3,0.1,0.06]", "boundary.front={type=\"wall\"}", "boundary.back={type=\"wall\"}",
                    "initial.soil=[{shape=\"box\", lower=[0,0,0], upper=[0.1,0.05,0.03]}]"});
  Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(overrides), "");
  const RunSummary s = sim.run();
  Collapse3d o;
  const Grid& g = sim.grid();
  o.nx = g.nx(), o.ny = g.ny(), o.nz = g.nz();
  o.c = gather_to_root(g, sim.soil()->soil_fraction());
  o.u = gather_to_root(g, sim.flow().velocity(0));
  o.v = gather_to_root(g, sim.flow().velocity(1));
  o.w = gather_to_root(g, sim.flow().velocity(2));
  o.sides = sim.flow().side_forces();
  o.obstacle = sim.flow().obstacle_force();
  o.kinetic = sim.soil()->budget(sim.flow()).kinetic_energy;
  o.volume_error = std::abs(s.soil_volume_error);
  return o;
}

// The collapse against the same with its floor, west wall and front wall built of three layers of
// blocked cells each (the obstacles after `obstacle=` in `built_obstacles`, the domain's walls in
// `walls`): the flow must be the same to `tolerance` (relative; round-off, 1e-9), and the obstacle must
// carry what the floor and the two walls carried. Returns the kinetic energy at the end.
double expect_built_walls_are_the_domains(const std::string& walls, const std::string& built_obstacles,
                                          const char* what, double tolerance = 1e-9) {
  std::vector<std::string> plain_case{"mesh.cells=[30,10,6]", "mesh.lower=[0,0,0]"};
  if (!walls.empty()) plain_case.push_back(walls);
  const Collapse3d plain = collapse_3d(plain_case);
  const Collapse3d built =
      collapse_3d({"mesh.cells=[33,13,9]", "mesh.lower=[-0.03,-0.03,-0.03]", "obstacle=" + built_obstacles});
  if (!test::is_root()) return plain.kinetic;
  double largest = 0.0, scale = 0.0, c_diff = 0.0, blocked_values = 0.0;
  for (int k = 0; k < built.nz; ++k)
    for (int j = 0; j < built.ny; ++j)
      for (int i = 0; i < built.nx; ++i) {
        const size_t n = (size_t(k) * built.ny + j) * built.nx + i;
        if (i < 3 || j < 3 || k < 3) {  // blocked: no soil, at rest
          blocked_values = std::max({blocked_values, std::abs(built.c[n]), std::abs(built.u[n]), std::abs(built.v[n]),
                                     std::abs(built.w[n])});
          continue;
        }
        const size_t m = (size_t(k - 3) * plain.ny + (j - 3)) * plain.nx + (i - 3);
        largest = std::max({largest, std::abs(built.u[n] - plain.u[m]), std::abs(built.v[n] - plain.v[m]),
                            std::abs(built.w[n] - plain.w[m])});
        scale = std::max({scale, std::abs(plain.u[m]), std::abs(plain.v[m]), std::abs(plain.w[m])});
        c_diff = std::max(c_diff, std::abs(built.c[n] - plain.c[m]));
      }
  std::array<double, 3> carried{};  // what the west wall, the floor and the front wall carried
  for (Side s : {Side::west, Side::south, Side::front})
    for (int a = 0; a < 3; ++a) carried[a] += plain.sides[int(s)][a];
  std::printf("3D collapse to t = 0.2 s with a floor and two walls of blocked cells against the domain's own (%s): "
              "velocities apart by %.2e m/s of %.3f, soil fractions by %.2e, kinetic energy %.12g / %.12g J, soil "
              "volume error %.1e; in the blocked cells |c|, |v| at most %.1e; obstacle force (%.6f, %.6f, %.6f) N "
              "against the floor and walls' (%.6f, %.6f, %.6f)\n",
              what, largest, scale, c_diff, built.kinetic, plain.kinetic, built.volume_error, blocked_values,
              built.obstacle[0], built.obstacle[1], built.obstacle[2], carried[0], carried[1], carried[2]);
  EXPECT_GT(scale, 0.3);  // the block is collapsing
  EXPECT_LT(largest, tolerance * scale);
  EXPECT_LT(c_diff, tolerance);
  EXPECT_NEAR(built.kinetic, plain.kinetic, tolerance * plain.kinetic);
  EXPECT_LT(built.volume_error, 1e-12);
  EXPECT_EQ(blocked_values, 0.0);
  const double weight_scale = std::abs(carried[1]);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(built.obstacle[a], carried[a], tolerance * weight_scale) << a;
  for (Side s : {Side::west, Side::south, Side::front})  // nothing flows along the domain's sides behind them
    for (int a = 0; a < 3; ++a) EXPECT_EQ(built.sides[int(s)][a], 0.0) << side_name(s) << a;
  return plain.kinetic;
}

// Where two or three of the built walls meet, the blocked cells behind both hold the domain's edge and
// corner ghosts (mirrored across each wall in turn); mirrored across one wall only, the kinetic energy
// came out 1e-3 apart.
TEST(Obstacles3d, BlockedFloorAndWallsAreTheDomainsOwn) {
  expect_built_walls_are_the_domains(
      "", "[{shape=\"box\", lower=[-1,-1,-1], upper=[1,0,1]}, {shape=\"box\", lower=[-1,-1,-1], upper=[0,1,1]}, "
          "{shape=\"box\", lower=[-1,-1,-1], upper=[1,1,0]}]",
      "walls of the soil's own friction");
}

// The floor built as the ground under a height map (terrain from an elevation model, flat here at the
// domain's floor): the same flow as on the domain's own floor, to round-off.
TEST(Obstacles3d, AFloorOfAHeightMapIsTheDomainsOwn) {
  expect_built_walls_are_the_domains(
      "", "[{shape=\"height_map\", origin=[-1,-1], spacing=[2,2], heights=[[0,0],[0,0]]}, "
          "{shape=\"box\", lower=[-1,-1,-1], upper=[0,1,1]}, {shape=\"box\", lower=[-1,-1,-1], upper=[1,1,0]}]",
      "the floor of a height map");
}

// The same with walls of their own friction (`friction_angle`, `adhesion`), each below the soil's
// friction in simple shear (tan 18.4 deg), so that the soil slides on all three: obstacles of the same
// friction are the same walls. Each blocked cell takes its own obstacle's friction (the floor's cells
// are listed last, under the corners of the walls). The two runs agree to round-off for 22 steps; at
// the 23rd the soil's front reaches the corner of the floor and the front wall, and there the PLIC
// normal that gives a wall face its soil fraction (wetted_side_fraction) changes its choice on the
// round-off of the cell widths (0.13 / 13 against 0.1 / 10 m): the face fraction moves by 8e-5 of
// itself, and at t = 0.2 s the velocities are 5.6e-4 of the largest apart, the kinetic energy 5.4e-6,
// the forces 3.6e-6 (measured).
TEST(Obstacles3d, BlockedFloorAndWallsOfTheirOwnFrictionAreTheDomainsOwn) {
  const double own = collapse_3d({"mesh.cells=[30,10,6]", "mesh.lower=[0,0,0]"}).kinetic;
  const double sliding = expect_built_walls_are_the_domains(
      "boundary={west={type=\"wall\", friction_angle=16.0}, east={type=\"atmosphere\"}, "
      "south={type=\"wall\", friction_angle=10.0}, north={type=\"atmosphere\"}, "
      "front={type=\"wall\", friction_angle=12.0, adhesion=5.0}, back={type=\"wall\"}}",
      "[{shape=\"box\", lower=[-1,-1,-1], upper=[0,1,1], friction_angle=16.0}, "
      "{shape=\"box\", lower=[-1,-1,-1], upper=[1,1,0], friction_angle=12.0, adhesion=5.0}, "
      "{shape=\"box\", lower=[-1,-1,-1], upper=[1,0,1], friction_angle=10.0}]",
      "walls of their own friction", 2e-3);
  if (!test::is_root()) return;
  std::printf("kinetic energy at t = 0.2 s on walls of their own friction %.6f J, on walls of the soil's %.6f J\n",
              sliding, own);
  EXPECT_GT(sliding, 1.5 * own);  // the soil slides on the smoother walls: the friction is the walls'
}

// A heavy layer at rest on terrain of layers: a bed 2.5 cm thick with a mound 7.5 x 6.25 x 7.5 cm on
// it in the middle of a 0.2 m cube, the layer's surface cutting a row of cells: it stays at rest, its
// pressure hydrostatic, and the bed and the mound carry its weight.
TEST(Obstacles3d, LayerAtRestOnAMound) {
  const CaseConfig config = parse_case(
      test::resting_layer_case,
      {"mesh.cells=[16,16,16]", "mesh.lower=[0,0,0]", "mesh.upper=[0.2,0.2,0.2]", "physics.gravity=[0,-9.81,0]",
       "boundary.front={type=\"wall\"}", "boundary.back={type=\"wall\"}", "time.max_steps=20",
       "numerics.pressure_coupling=\"coupled\"",
       "obstacle=[{shape=\"box\", lower=[-1,-1,-1], upper=[1,0.025,1]}, "
       "{shape=\"box\", lower=[0.0625,0.0,0.0625], upper=[0.1375,0.0625,0.1375]}]"});
  const test::LayerOnTerrain r = test::run_layer_on_terrain(config, [](double x, double y, double z) {
    const bool mound = x > 0.0625 && x < 0.1375 && z > 0.0625 && z < 0.1375 && y < 0.0625;
    return !(y < 0.025 || mound);
  });
  if (!test::is_root()) return;
  std::printf("layer at rest on a mound, 16^3 cells, after %ld steps: max |v| = %.3e m/s, pressure change %.3e of its "
              "largest, soil volume error %.1e; the walls and the terrain carry its weight %.12g N to %.1e (the "
              "terrain to %.1e; horizontal %.1e, %.1e N)\n",
              r.steps, r.speed, r.pressure_change, r.volume_change, r.weight, r.carried - 1, -r.obstacle[1] / r.weight - 1,
              r.obstacle[0], r.obstacle[2]);
  EXPECT_EQ(r.steps, 20);
  EXPECT_LT(r.speed, 1e-8);
  EXPECT_LT(r.pressure_change, 1e-10);
  EXPECT_LT(std::abs(r.volume_change), 1e-12);
  EXPECT_NEAR(r.carried, 1.0, 1e-10);
  EXPECT_NEAR(-r.obstacle[1] / r.weight, 1.0, 1e-10);  // the bed covers the floor: the terrain carries it all
  EXPECT_LT(std::abs(r.obstacle[0]), 1e-9 * r.weight);  // the mound is pushed alike from either side
  EXPECT_LT(std::abs(r.obstacle[2]), 1e-9 * r.weight);
}

}  // namespace
}  // namespace granflow

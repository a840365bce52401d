// Periodic west and east sides on a mesh of layers: a strip that runs on through its ends, as on a
// planar mesh. A flow that does not vary along z, between slip front and back sides, is the planar
// run in every layer: the soil and air crossing the join, the budget's potential energy carried on
// through it (SoilPhase's join moment), the coupled solve's and the projection's rows across it.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

struct StripRun {
  std::vector<double> c, u, v, w;
  SoilBudget budget;
  double time = 0.0;
  int nx = 0, ny = 0, nz = 1;
};

StripRun run_strip(const std::string& case_file, const std::vector<std::string>& overrides) {
  Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path(case_file), overrides), "");
  sim.run();
  StripRun r;
  const Grid& g = sim.grid();
  r.nx = g.nx(), r.ny = g.ny(), r.nz = g.dimension() == 3 ? g.nz() : 1;
  r.c = gather_to_root(g, sim.soil()->soil_fraction());
  r.u = gather_to_root(g, sim.flow().velocity(0));
  r.v = gather_to_root(g, sim.flow().velocity(1));
  if (g.dimension() == 3) r.w = gather_to_root(g, sim.flow().velocity(2));
  r.budget = sim.soil()->budget(sim.flow());
  r.time = sim.time();
  return r;
}

struct Apart {
  double velocity = 0.0, speed = 0.0, fraction = 0.0, w = 0.0, kinetic = 0.0, potential = 0.0, dissipation = 0.0;
  double air_w = 0.0;  // with soil_only: the largest |w| in the other cells
};

// The layers' fields against the planar run's (with soil_only, in the cells at least half soil only),
// and the budgets per metre of depth.
Apart compare(const StripRun& planar, const StripRun& layers, double depth, bool soil_only = false) {
  Apart a;
  for (int k = 0; k < layers.nz; ++k)
    for (int j = 0; j < planar.ny; ++j)
      for (int i = 0; i < planar.nx; ++i) {
        const size_t p = size_t(j) * planar.nx + i, l = (size_t(k) * layers.ny + j) * layers.nx + i;
        a.fraction = std::max(a.fraction, std::abs(layers.c[l] - planar.c[p]));
        if (soil_only && !(planar.c[p] >= 0.5)) {
          a.air_w = std::max(a.air_w, std::abs(layers.w[l]));
          continue;
        }
        a.velocity = std::max({a.velocity, std::abs(layers.u[l] - planar.u[p]), std::abs(layers.v[l] - planar.v[p])});
        a.speed = std::max({a.speed, std::abs(planar.u[p]), std::abs(planar.v[p])});
        a.w = std::max(a.w, std::abs(layers.w[l]));
      }
  auto relative = [](double x, double y) { return std::abs(x - y) / std::abs(y); };
  a.kinetic = relative(layers.budget.kinetic_energy / depth, planar.budget.kinetic_energy);
  a.potential = relative(layers.budget.potential_energy / depth, planar.budget.potential_energy);
  a.dissipation = relative(layers.budget.dissipation_rate / depth, planar.budget.dissipation_rate);
  return a;
}

std::vector<std::string> layered(std::vector<std::string> o, const std::string& cells, const std::string& upper,
                                 const std::string& gravity) {
  o.insert(o.end(), {"mesh.cells=" + cells, "mesh.lower=[0, 0, 0]", "mesh.upper=" + upper, "physics.gravity=" + gravity,
                     "boundary.front={type=\"slip\"}", "boundary.back={type=\"slip\"}"});
  return o;
}

// cases/bagnold_chute.toml (the mu(I) layer on a periodic strip at 24 deg, the coupled solve) from rest
// to t = 1 s, when it flows at 0.2 m/s on top and has crossed the join 50 times over: on 4 x 30 x 2
// cells, 1 mm deep, its soil and air are the planar run's in both layers. Measured: velocities 1.2e-10
// m/s apart of 0.199, w 2e-13, soil fractions 2e-12, energies 7e-10 of themselves. While the open top's inflow lost the dynamic head of the whole speed, not of
// the normal velocity alone (FlowSolver's atmosphere_pressure), a circulation grew in and out through
// the top in both runs (at t = 5 s |v| up to 0.021 m/s in the planar run, where the air should move
// along x only) and in 3D in the x-z plane (|w| up to 2.6e-4 m/s at t = 1 s, 7e-3 at t = 5 s), while
// the soil still agreed; the air is asserted here as the soil is.
TEST(Periodic3d, AChuteOfLayersIsThePlanarOne) {
  const std::vector<std::string> common = {"time.end=1.0", "output.progress_seconds=0"};
  const StripRun planar = run_strip("cases/bagnold_chute.toml", common);
  const StripRun layers =
      run_strip("cases/bagnold_chute.toml",
                layered({"time.end=1.0", "output.progress_seconds=0",
                         "output.line=[{name=\"profile\", start=[0.001, 0.00025, 0.0005], end=[0.001, 0.00975, 0.0005]}]"},
                        "[4, 30, 2]", "[0.002, 0.015, 0.001]", "[3.9900865, -8.9618809, 0]"));
  if (!test::is_root()) return;
  const Apart soil = compare(planar, layers, 0.001, true), a = compare(planar, layers, 0.001);
  std::printf("periodic chute on two layers against the planar run at t = %.3f s: velocities %.2e m/s apart of %.3f "
              "(in the soil %.2e), w at most %.1e (in the air %.1e), soil fractions %.1e; kinetic energy %.1e, "
              "potential %.1e, dissipation rate %.1e of themselves\n",
              layers.time, a.velocity, a.speed, soil.velocity, a.w, soil.air_w, a.fraction, a.kinetic, a.potential,
              a.dissipation);
  EXPECT_GT(a.speed, 0.15);  // it flows
  EXPECT_LT(a.velocity, 1e-6 * a.speed);
  EXPECT_LT(a.w, 1e-9 * a.speed);
  EXPECT_LT(a.fraction, 1e-8);
  EXPECT_LT(a.kinetic, 1e-5);
  EXPECT_LT(a.potential, 1e-5);
  EXPECT_LT(a.dissipation, 1e-5);
}

// A water column on a periodic strip tilted by gravity along x (cases/water_dam_break.toml's fluids,
// the projection, the Newtonian mixture), whose collapse runs through the join: 24 x 12 x 2 cells, the
// planar run in both layers to t = 0.05 s. Measured: velocities 2e-9 m/s apart of 0.80, kinetic energy 2e-9.
TEST(Periodic3d, WaterOnAStripOfLayersIsThePlanarOneUnderTheProjection) {
  const std::vector<std::string> common = {"time.end=0.05", "output.progress_seconds=0", "output.fields=false",
                                           "boundary.west={type=\"periodic\"}", "boundary.east={type=\"periodic\"}",
                                           "initial.soil=[{shape=\"box\", lower=[0.0, 0.0], upper=[0.06, 0.06]}]"};
  std::vector<std::string> planar_case = common;
  planar_case.insert(planar_case.end(), {"mesh.cells=[24, 12]", "mesh.upper=[0.24, 0.12]", "physics.gravity=[2.0, -9.81]"});
  const StripRun planar = run_strip("cases/water_dam_break.toml", planar_case);
  const StripRun layers =
      run_strip("cases/water_dam_break.toml", layered(common, "[24, 12, 2]", "[0.24, 0.12, 0.02]", "[2.0, -9.81, 0]"));
  if (!test::is_root()) return;
  const Apart a = compare(planar, layers, 0.02);
  std::printf("water on a periodic strip of two layers against the planar run at t = %.3f s: velocities %.2e m/s apart "
              "of %.3f, w at most %.1e, soil fractions %.1e; kinetic energy %.1e, potential %.1e of themselves\n",
              layers.time, a.velocity, a.speed, a.w, a.fraction, a.kinetic, a.potential);
  EXPECT_GT(a.speed, 0.5);
  EXPECT_LT(a.velocity, 1e-6 * a.speed);
  EXPECT_LT(a.w, 1e-9 * a.speed);
  EXPECT_LT(a.fraction, 1e-8);
  EXPECT_LT(a.kinetic, 1e-6);
  EXPECT_LT(a.potential, 1e-6);
}

}  // namespace
}  // namespace granflow

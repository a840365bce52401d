// Soil at rest must stay at rest on the discrete level: a heavy layer under air (density ratio
// 2650:1, viscosity ratio 1e8), and a granular block too strong to fail.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

// A layer at rest for 1000 steps: largest speed and the change of the pressure, relative.
void check_resting_layer(const std::string& east_boundary, const char* label) {
  // The layer top cuts a row of cells at c = 0.4, so the interface is not aligned with faces.
  const CaseConfig config =
      parse_case(test::resting_layer_case, {"boundary.east={type = \"" + east_boundary + "\"}"});
  Simulation sim(PETSC_COMM_WORLD, config, "");
  Vec p0;
  VecDuplicate(sim.flow().pressure().global(), &p0);
  VecCopy(sim.flow().pressure().global(), p0);
  const RunSummary s = sim.run();
  EXPECT_EQ(s.steps, 1000);
  const double speed = sim.flow().max_speed();
  double p_scale, p_change;
  VecNorm(p0, NORM_INFINITY, &p_scale);
  VecAXPY(p0, -1.0, sim.flow().pressure().global());
  VecNorm(p0, NORM_INFINITY, &p_change);
  VecDestroy(&p0);
  std::printf("resting layer (%s) after %ld steps: max |v| = %.3e m/s, max |p - p_hydrostatic| / max p = %.3e\n",
              label, s.steps, speed, p_change / p_scale);
  EXPECT_LT(speed, 1e-8);
  EXPECT_LT(p_change / p_scale, 1e-10);

  // The sides carry the layer: the floor its weight (the mixture's mass, to round-off on this uniform
  // mesh: the face forces telescope to the side pressures plus the weight), the side walls its
  // thrust, which cancel, and which a soil pressure rho_s g (h - y) makes rho_s g h^2 / 2.
  const auto force = sim.flow().side_forces();
  const auto at = [&](Side side) { return force[static_cast<int>(side)]; };
  const double weight = sim.soil()->budget(sim.flow()).mixture_mass * 9.81;
  double vertical = 0.0;
  for (const auto& f : force) vertical += f[1];
  const double h = 0.1025, thrust = 2650.0 * 9.81 * h * h / 2;
  std::printf("  floor carries %.12g N/m of a weight of %.12g N/m; west wall thrust %.6g N/m against rho g h^2/2 = %.6g, "
              "east %.6g\n", -vertical, weight, -at(Side::west)[0], thrust, at(Side::east)[0]);
  EXPECT_NEAR(-vertical / weight, 1.0, 1e-10);
  EXPECT_NEAR(at(Side::east)[0] / -at(Side::west)[0], 1.0, 1e-10);
  EXPECT_NEAR(-at(Side::west)[0] / thrust, 1.0, 0.01);
}

TEST(RestingSoil, FlatHeavyLayerStaysAtRestWithHydrostaticPressure) { check_resting_layer("wall", "closed sides"); }

// The layer runs out through an open side: the boundary's pressure is the hydrostatic head of its own
// column of soil and air, so nothing flows in or out.
TEST(RestingSoil, FlatHeavyLayerAcrossAnOpenSideStaysAtRest) { check_resting_layer("atmosphere", "open east side"); }

// Column heights sum_j c dy and row widths sum_i c dx of the soil, gathered on every rank.
std::vector<double> extents(const Grid& g, const Field& c_field) {
  auto c = gather_to_root(g, c_field);
  c.resize(size_t(g.nx()) * g.ny());
  MPI_Bcast(c.data(), int(c.size()), MPI_DOUBLE, 0, g.comm());
  std::vector<double> e(g.nx() + g.ny(), 0.0);
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      e[i] += c[size_t(j) * g.nx() + i] * g.dy(j);
      e[g.nx() + j] += c[size_t(j) * g.nx() + i] * g.dx(i);
    }
  return e;
}

// The block stands only if two things hold. (1) The velocity and the pressure are solved together
// (numerics.pressure_coupling = coupled): the projection's correction moves the faces at the block's
// sides with the inviscid mobility dt / rho_f, and the block leaks there by 4-6 cells in 1 s.
// (2) The faces between soil and air carry the soil's viscosity (soil.face_fraction = face): with the
// two cells' mixtures the face at the side of the block has the air's viscosity, the air is driven
// round the top corner, a trace of soil (c = 0.002, which the arctan density makes 19 kg/m^3) is
// drawn out and falls beside the block, and the surface moves by 0.25 cells in 1 s. With both, the
// largest displacement is 2e-5 cells (docs/method.md).
TEST(RestingSoil, CohesiveBlockThatCannotFailStaysPut) {
  // The Bui et al. block with a cohesion far above rho g h: the yield stress is never reached.
  const CaseConfig config = test::bui2008_case_at_courant_one(
      {"mesh.cells=[150,50]", "time.end=1.0", "time.max_dt=0.01", "soil.rheology.cohesion=1e5",
       "numerics.pressure_coupling=coupled", "soil.face_fraction=face", "output.progress_seconds=0"});
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const Grid& g = sim.grid();
  const auto before = extents(g, sim.soil()->soil_fraction());
  sim.run();
  const auto after = extents(g, sim.soil()->soil_fraction());
  double worst = 0.0;  // in cells
  for (size_t k = 0; k < before.size(); ++k) {
    const double h = k < size_t(g.nx()) ? g.dy(0) : g.dx(0);
    test::keep_largest(worst, std::abs(after[k] - before[k]) / h);
  }
  std::printf("cohesive block after 1 s: largest surface displacement %.3e cells, max |v| %.3e m/s\n", worst,
              sim.flow().max_speed());
  // Required: under 0.1 cell. Measured 1.9e-5 cells and 1.1e-8 m/s; the bounds below catch a
  // regression that creep at the regularisation's floor or a stray flux would bring, long before 0.1.
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(sim.flow().max_speed(), 1e-6);
}

// A low mound of the Bui et al. soil on the floor, 5 mm high (1.25 cells) and sloping at 4.8 degrees,
// well below its 19.8 degree friction angle: it must not move, nor drive the air. Its fringe cells
// hold a few per cent of soil, which the arctan rule makes heavy (30 % of the soil's density at
// c = 0.05) but nearly inviscid. The floor under them is soil all the same (the PLIC line lies along
// it), and the floor face takes that fraction (soil.face_fraction = face, docs/method.md). With the
// cells' own c instead, the fringe slides over the floor under its weight: its column heights move
// by 1.7e-3 cells in 0.5 s and it drives the air at 0.25 m/s, which halves the step. With the floor's
// covered fraction they move by 2e-6 cells and the air stays below 2e-3 m/s.
TEST(RestingSoil, LowMoundOnTheFloorStaysPut) {
  std::ifstream in(test::repo_path("cases/bui2008_experiment.toml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string block = "shape = \"box\"\nlower = [0.0, 0.0]\nupper = [0.2, 0.1]\n";
  const auto at = text.find(block);
  ASSERT_NE(at, std::string::npos) << "the case's initial block changed; update this test";
  text.replace(at, block.size(), "shape = \"polygon\"\npoints = [[0.05, 0.0], [0.17, 0.0], [0.11, 0.005]]\n");
  const CaseConfig config = parse_case(
      text, test::bui2008_at_courant_one({"mesh.cells=[150,50]", "time.end=0.5", "output.progress_seconds=0"}));
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const Grid& g = sim.grid();
  const auto before = extents(g, sim.soil()->soil_fraction());
  const RunSummary run = sim.run();
  const auto after = extents(g, sim.soil()->soil_fraction());
  double worst = 0.0;  // in cells
  for (size_t k = 0; k < before.size(); ++k) {
    const double h = k < size_t(g.nx()) ? g.dy(0) : g.dx(0);
    test::keep_largest(worst, std::abs(after[k] - before[k]) / h);
  }
  const double speed = sim.flow().max_speed();
  std::printf("low mound after 0.5 s (%ld steps): largest surface displacement %.3e cells, max |v| %.3e m/s\n",
              run.steps, worst, speed);
  EXPECT_LT(worst, 1e-4);
  EXPECT_LT(speed, 1e-2);
}

}  // namespace
}  // namespace granflow

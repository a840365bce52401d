// soil.yield_pressure = "lithostatic_floor": a cell's yield stress takes its own pressure, but at least the
// weight of the soil above its centre in its column, rho_s |g| (sum of c dy above + c dy / 2 of its own).
// A layer 0.425 m deep (the top cell half full) in a simple shear u = gamma y, with the pressure set
// to zero everywhere but one column, where it is twice the overburden: the viscosity of each full,
// interior cell must be the rheology's at the overburden (at its own pressure in that column), and
// without the floor the rheology's at zero pressure (the floor of the regularisation, mu_min).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "models/rheology/granular_rheology.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double soil_top = 0.425;  // m: 8 full cells of 0.05 m and the ninth half full
constexpr double shear_rate = 2.0;  // 1/s, du/dy
constexpr double rho_s = 2000.0, g = 9.81;
constexpr int pressed_column = 2;   // where the cell pressure is twice the overburden

std::string layer_case(const std::string& yield_pressure) {
  return R"(
[mesh]
cells = [4, 20]
upper = [0.4, 1.0]
[time]
end = 1.0
dt = 1e-3
[physics]
gravity = [0.0, -9.81]
[air]
density = 1.0
viscosity = 1e-5
[soil]
density = 2000.0
yield_pressure = ")" + yield_pressure + R"("
strain_rate = "cell"
face_fraction = "cells"
[soil.rheology]
model = "drucker_prager"
friction_angle = 30.0
regularisation = "exponential"
m = 1e5
mu_min = 1e-3
[mixture]
density = "linear"
viscosity = "linear"
[[initial.soil]]
shape = "box"
lower = [0.0, 0.0]
upper = [0.4, 0.425]
[boundary]
west = { type = "periodic" }
east = { type = "periodic" }
south = { type = "wall" }
north = { type = "atmosphere" }
[numerics]
air_band = 0
[output]
progress_seconds = 0
)";
}

// The cell viscosities (gathered to rank 0) that the soil gives the flow in the set-up above.
std::vector<double> viscosities(const std::string& yield_pressure) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(layer_case(yield_pressure)), "");
  const Grid& grid = sim.grid();
  FlowSolver& flow = sim.flow();
  test::fill(grid, flow.velocity(0), [](double, double y) { return shear_rate * y; });
  test::fill(grid, flow.velocity(1), [](double, double) { return 0.0; });
  for (int a = 0; a < 2; ++a) flow.velocity(a).scatter_to_local();
  test::fill(grid, flow.pressure(), [&grid](double x, double y) {
    const bool pressed = x > grid.xc(pressed_column) - 0.01 && x < grid.xc(pressed_column) + 0.01;
    return pressed ? 2.0 * rho_s * g * std::max(soil_top - y, 0.0) : 0.0;
  });
  flow.pressure().scatter_to_local();
  SoilPhase& soil = *sim.soil();
  soil.refresh(flow);
  soil.update_properties(flow);
  return gather_to_root(grid, flow.viscosity());
}

TEST(LithostaticFloor, YieldStressAtLeastTheWeightOfTheSoilAbove) {
  const auto floor = viscosities("lithostatic_floor");
  const auto cell = viscosities("cell");
  if (!test::is_root()) return;
  const rheology::GranularRheology rheology(*parse_case(layer_case("cell")).soil->rheology);
  const rheology::StrainRate rate = rheology::planar_strain_rate(0.0, 0.0, 0.5 * shear_rate);
  const int nx = 4;
  int checked = 0;
  // Rows 1-7: full of soil, and their central differences of u are the exact shear rate (row 0 takes
  // the wall's ghost).
  for (int j = 1; j <= 7; ++j)
    for (int i = 0; i < nx; ++i) {
      const double depth = soil_top - (0.05 * j + 0.025);
      const double pressure = (i == pressed_column ? 2.0 : 1.0) * rho_s * g * depth;
      const double expected = rheology.dynamic_viscosity(rate, pressure);
      EXPECT_NEAR(floor[size_t(j) * nx + i], expected, 1e-12 * expected) << "cell " << i << ", " << j;
      const double without = i == pressed_column ? expected : rheology.dynamic_viscosity(rate, 0.0);
      EXPECT_NEAR(cell[size_t(j) * nx + i], without, 1e-12 * without) << "cell " << i << ", " << j;
      ++checked;
    }
  EXPECT_EQ(checked, 28);
  // The floor matters: at 0.2 m of depth the yield stress of 2000 kg/m^3 at 30 degrees is some 2 kPa.
  EXPECT_GT(floor[size_t(4) * nx + 0], 100.0 * cell[size_t(4) * nx + 0]);
}

}  // namespace
}  // namespace granflow

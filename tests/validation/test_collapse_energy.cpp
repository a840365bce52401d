// Energy budget and soil volume of a granular collapse: the bui2008_experiment case on 150 x 50 cells
// to t = 0.6 s, when most of the potential energy has been released. With a linear density
// interpolation the mixture's mass is the soil's, and the potential energy released must equal the
// kinetic plus the viscously dissipated energy; the time discretisation (backward Euler, upwinded
// convection) dissipates a little more, so the budget may fall short by a few per cent, never exceed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "solver/simulation.hpp"
#include "../verification/test_support.hpp"

namespace granflow {
namespace {

// The collapse of the Bui et al. case with `overrides` to its end, into the test's directory `name`:
// its run and history (rank 0's; empty elsewhere), and the energy released against that accounted for.
struct CollapseBudget {
  RunSummary run;
  std::map<std::string, std::vector<double>> history;
  double released = 0.0;   // potential plus initial kinetic energy given up, J/m
  double accounted = 0.0;  // kinetic energy at the end plus the energy dissipated, J/m
  double last(const std::string& column) const { return history.at(column).back(); }
};
CollapseBudget run_collapse(const std::string& name, const std::vector<std::string>& overrides) {
  const auto out = test::output_dir(name);
  std::filesystem::remove_all(out);
  Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(overrides), out);
  CollapseBudget b{sim.run()};
  if (!test::is_root()) return b;
  b.history = test::read_csv((out / "history.csv").string());
  const auto& h = b.history;
  if (h.at("time").size() < 2) return b;
  b.released = h.at("potential_energy").front() + h.at("kinetic_energy").front() - h.at("potential_energy").back();
  b.accounted = h.at("kinetic_energy").back() + h.at("dissipated_energy").back();
  return b;
}

TEST(GranularCollapse, EnergyBudgetClosesWithLinearDensity) {
  // the projection, as the case was written for it (docs/validation.md)
  const CollapseBudget b = run_collapse(
      "collapse_energy", test::with_bui2008_projection({"output.progress_seconds=0", "output.interval=0.3", "time.end=0.6",
                                                        "mesh.cells=[150, 50]", "mixture.density=\"linear\""}));
  if (!test::is_root()) return;
  ASSERT_GT(b.history.at("time").size(), 10u);
  const double volume_error = std::abs(b.last("soil_volume") / b.history.at("soil_volume").front() - 1.0);
  std::printf("collapse 150 x 50 to t = %.2f s (%ld steps): released %.4f J/m, kinetic + dissipated %.4f J/m (%+.2f %%), "
              "soil volume error %.2e\n",
              b.run.time, b.run.steps, b.released, b.accounted, 100 * (b.accounted / b.released - 1), volume_error);
  EXPECT_GT(b.released, 5.0);  // the block has collapsed: a third of its potential energy is gone
  // Short by 2.8 % here: the numerical dissipation the recorded one misses; an excess would be energy
  // from nowhere.
  EXPECT_LT(b.accounted / b.released - 1.0, 0.0);
  EXPECT_GT(b.accounted / b.released - 1.0, -0.05);
  EXPECT_LT(volume_error, 1e-10);
}

// The same budget with the shipped numerics (the coupled solve) on a floor smoother than the soil
// (`boundary.south.friction_angle = 15`, below the soil's tan 18.4 deg in simple shear): the pile
// slides on the floor, and what the floor's friction dissipates is counted with the rest, from the
// floor face's viscosity (docs/method.md, "Boundaries"). Measured: -2.5 %, the one-cell toe at 0.508 m
// against 0.476 on the soil's own friction (-2.8 % there). The floor's faces dissipate 29 % of the energy
// released: without them the budget comes to -31.6 % and the test fails.
TEST(GranularCollapse, EnergyBudgetClosesOnASmootherFloor) {
  const CollapseBudget b = run_collapse(
      "collapse_energy_smooth_floor",
      {"output.progress_seconds=0", "output.interval=0.3", "output.fields=false", "time.end=0.6", "mesh.cells=[150, 50]",
       "mixture.density=\"linear\"", "boundary.south={type = \"wall\", friction_angle = 15.0}"});
  if (!test::is_root()) return;
  ASSERT_GT(b.history.at("time").size(), 10u);
  std::printf("collapse 150 x 50 on a floor of 15 deg to t = %.2f s (%ld steps): released %.4f J/m, kinetic + "
              "dissipated %.4f J/m (%+.2f %%), one-cell toe %.3f m, soil out %.2e m^2\n",
              b.run.time, b.run.steps, b.released, b.accounted, 100 * (b.accounted / b.released - 1),
              b.last("toe_one_cell"), b.last("soil_outflow"));
  EXPECT_LT(b.accounted / b.released - 1.0, 0.0);
  EXPECT_GT(b.accounted / b.released - 1.0, -0.05);
  EXPECT_GT(b.last("toe_one_cell"), 0.49);  // the floor's friction did act: 0.476 m without it
  // A fragment of the front may leave through the open side with its energy: 3e-4 of the soil here.
  EXPECT_LT(b.last("soil_outflow"), 1e-3 * b.history.at("soil_volume").front());
}

}  // namespace
}  // namespace granflow

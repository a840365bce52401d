// Several VoF sweeps per flow step (time.interface_substeps): the bui2008_experiment collapse on
// 75 x 25 cells to t = 0.4 s, once with the step sized by one sweep (Courant 0.5) and once with two
// sweeps per step (Courant 1). Once the step has grown from its initial 1e-4 s (by t = 0.1 s, after
// 39 and 32 steps here), the second must take about half the steps;
// it must conserve the soil to round-off and put the front within two cells of the first's (measured
// 1.35 cells, 0.4550 and 0.4658 m; 150 x 50 puts them 2.9 cells of its own apart, 0.4655 and 0.4770 m:
// the thin front depends on the step since the momentum a step starts with keeps the kinetic energy it
// was carried with, docs/validation.md; before, within a cell).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "solver/simulation.hpp"
#include "../verification/test_support.hpp"

namespace granflow {
namespace {

struct Outcome {
  long steps = 0;
  double volume_error = 0.0;
  double toe = 0.0;  // c = 0.5 contour toe at the end (m)
  long steps_after_ramp = 0;  // steps ending after t = 0.1 s
};

Outcome run_collapse(int substeps, double courant) {
  const auto out = test::output_dir("substeps_" + std::to_string(substeps));
  std::filesystem::remove_all(out);
  const CaseConfig config = test::bui2008_case_at_courant_one(
      {"output.progress_seconds=0", "output.interval=0.4", "time.end=0.4", "mesh.cells=[75, 25]",
       "time.interface_substeps=" + std::to_string(substeps), "time.courant=" + std::to_string(courant)});
  Simulation sim(PETSC_COMM_WORLD, config, out);
  const RunSummary run = sim.run();
  Outcome o{run.steps, run.soil_volume_error, 0.0};
  if (test::is_root()) {
    auto history = test::read_csv((out / "history.csv").string());
    o.toe = history["toe_contour"].back();
    for (double t : history["time"]) o.steps_after_ramp += t > 0.1 ? 1 : 0;
  }
  return o;
}

TEST(InterfaceSubsteps, TwoSweepsPerStepHalveTheStepsAndKeepTheFront) {
  const Outcome one = run_collapse(1, 0.5), two = run_collapse(2, 1.0);
  const double dx = 0.6 / 75;
  std::printf("75 x 25 to t = 0.4 s: one sweep per step %ld steps (%ld after t = 0.1 s), toe %.4f m; two sweeps %ld "
              "steps (%ld), toe %.4f m (%.2f cells apart); soil volume error %.1e / %.1e\n",
              one.steps, one.steps_after_ramp, one.toe, two.steps, two.steps_after_ramp, two.toe,
              std::abs(two.toe - one.toe) / dx, one.volume_error, two.volume_error);
  EXPECT_LT(two.steps, one.steps);
  EXPECT_LT(std::abs(two.volume_error), 1e-12);
  if (test::is_root()) {
    EXPECT_LT(double(two.steps_after_ramp), 0.6 * double(one.steps_after_ramp));
    EXPECT_LT(std::abs(two.toe - one.toe), 2 * dx);
  }
}

}  // namespace
}  // namespace granflow

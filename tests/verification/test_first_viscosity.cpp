// The viscosity of a step's first outer iteration (numerics.first_viscosity = "look_ahead": the
// larger of those from u^n and from the velocity extrapolated to the end of the step) changes where
// the Picard iteration starts, never what it converges to. The Bui et al. collapse on 30 x 10 cells
// to t = 0.06 s (27 steps), each step's outer loop run to a velocity change of 1e-8: both starts
// must give the same flow. A look-ahead that left the extrapolated velocity in place of u^n, or
// took the soil's viscosity from it for good, would not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

struct Outcome {
  long steps = 0, outer_iterations = 0;
  std::vector<double> u, v;
};

Outcome run_converged_collapse(const std::string& first_viscosity) {
  const CaseConfig config =
      load_case(test::repo_path("cases/bui2008_experiment.toml"),
                {"output.progress_seconds=0", "mesh.cells=[30, 10]", "time.end=0.06", "output.interval=0.06",
                 "numerics.outer_iterations=400", "numerics.outer_tolerance=1e-8",
                 "numerics.first_viscosity=\"" + first_viscosity + "\""});
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const RunSummary s = sim.run();
  return {s.steps, s.outer_iterations, gather_to_root(sim.grid(), sim.flow().velocity(0)),
          gather_to_root(sim.grid(), sim.flow().velocity(1))};
}

TEST(FirstViscosity, LookAheadChangesTheStartNotTheConvergedStep) {
  const Outcome previous = run_converged_collapse("previous_step"), ahead = run_converged_collapse("look_ahead");
  EXPECT_EQ(previous.steps, ahead.steps);
  EXPECT_LT(previous.outer_iterations, 400 * previous.steps);  // every step's outer loop converged
  EXPECT_LT(ahead.outer_iterations, 400 * ahead.steps);
  if (!test::is_root()) return;
  double difference = 0.0, scale = 0.0;
  for (size_t k = 0; k < previous.u.size(); ++k) {
    difference = std::max({difference, std::abs(previous.u[k] - ahead.u[k]), std::abs(previous.v[k] - ahead.v[k])});
    scale = std::max({scale, std::abs(previous.u[k]), std::abs(previous.v[k])});
  }
  std::printf("collapse 30 x 10 to t = 0.06 s, outer loop to 1e-8: %ld steps, %ld / %ld outer iterations from u^n / "
              "looking ahead; largest velocity difference %.2e m/s of %.3f m/s\n",
              previous.steps, previous.outer_iterations, ahead.outer_iterations, difference, scale);
  EXPECT_LT(difference, 1e-6 * scale);
}

}  // namespace
}  // namespace granflow

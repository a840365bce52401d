// The first outer iterate of a step (numerics.first_iterate): extrapolating it from the last two
// steps must change where the outer loop starts, never what it converges to. The lid-driven cavity
// starting from rest (Re 100, 24 x 24, projection, 30 steps of 0.02 s) with the outer loop run to
// a change of 1e-10: both starts give the same velocities (a step that kept the extrapolated
// velocity as its old time level differs at the size of the velocity itself), and on
// this smooth transient the extrapolated start needs fewer outer iterations.
#include <gtest/gtest.h>

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
  long outer_iterations = 0;
  std::vector<double> u, v;
};

Outcome run_cavity(const std::string& first_iterate) {
  const CaseConfig config = load_case(
      test::repo_path("cases/lid_driven_cavity_re100.toml"),
      {"output.progress_seconds=0", "mesh.cells=[24, 24]", "time.adaptive=false", "time.dt=0.02", "time.end=0.6",
       "time.steady_tolerance=0", "numerics.pressure_coupling=\"projection\"", "numerics.outer_iterations=200",
       "numerics.outer_tolerance=1e-10", "solver.momentum.rtol=1e-12", "solver.pressure.rtol=1e-12",
       "numerics.first_iterate=\"" + first_iterate + "\""});
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const RunSummary s = sim.run();
  EXPECT_EQ(s.steps, 30);
  return {s.outer_iterations, gather_to_root(sim.grid(), sim.flow().velocity(0)),
          gather_to_root(sim.grid(), sim.flow().velocity(1))};
}

TEST(FirstIterate, ExtrapolationChangesTheStartNotTheConvergedStep) {
  const Outcome previous = run_cavity("previous_step"), extrapolated = run_cavity("extrapolated");
  if (!test::is_root()) return;
  double difference = 0.0, scale = 0.0;
  for (size_t k = 0; k < previous.u.size(); ++k) {
    difference = std::max({difference, std::abs(previous.u[k] - extrapolated.u[k]),
                           std::abs(previous.v[k] - extrapolated.v[k])});
    scale = std::max({scale, std::abs(previous.u[k]), std::abs(previous.v[k])});
  }
  std::printf("cavity Re 100, 24 x 24, 30 steps: outer iterations %ld from the previous step, %ld extrapolated; "
              "largest velocity difference %.2e of %.3f\n",
              previous.outer_iterations, extrapolated.outer_iterations, difference, scale);
  EXPECT_LT(difference, 1e-8 * scale);  // the outer loop stops at a change of 1e-10
  EXPECT_LT(extrapolated.outer_iterations, previous.outer_iterations);
}

}  // namespace
}  // namespace granflow

// Axisymmetric verification: Hagen-Poiseuille flow in a pipe of radius R, driven by fixed static
// pressures at its ends, against w(r) = G (R^2 - r^2) / (4 mu). The radial viscous flux r dw/dr is
// exact for the parabola on interior faces, so the error comes from the wall closure alone: it falls
// at second order with the two-point wall gradient, and vanishes to the solver tolerance with the
// quadratic one (numerics.wall_gradient = "quadratic").
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double R = 0.5, L = 0.01, G = 8.0, mu = 2.0;  // radius, length, -dp/dz, viscosity
double exact(double r) { return G * (R * R - r * r) / (4 * mu); }

// Largest |w - w_exact| over cell centres relative to the centre-line velocity.
double pipe_error(int nr, const char* wall_gradient = "two_point") {
  const std::string text = fmt::format(R"(
[mesh]
geometry = "axisymmetric"
cells = [{}, 2]
upper = [{}, {}]
[time]
end = 1e9
dt = 1.0
adaptive = false
steady_tolerance = 1e-12
max_steps = 400
[fluid]
density = 1.0
viscosity = {}
[boundary]
west = {{ type = "axis" }}
east = {{ type = "wall" }}
south = {{ type = "atmosphere", pressure = {}, pressure_kind = "static" }}
north = {{ type = "atmosphere", pressure = 0.0, pressure_kind = "static" }}
[numerics]
convection = "upwind"
outer_iterations = 4
outer_tolerance = 1e-12
wall_gradient = "{}"
[solver.momentum]
ksp_type = "preonly"
pc_type = "lu"
[solver.pressure]
ksp_type = "preonly"
pc_type = "lu"
[output]
progress_seconds = 0
)",
                                       nr, R, L, mu, G * L, wall_gradient);
  Simulation sim(PETSC_COMM_WORLD, parse_case(text), "");
  const RunSummary s = sim.run();
  EXPECT_TRUE(s.reached_steady_state) << s.steps << " steps";
  const Grid& g = sim.grid();
  const auto w = gather_to_root(g, sim.flow().velocity(1));
  const auto u = gather_to_root(g, sim.flow().velocity(0));
  double worst = 0.0, radial = 0.0;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        test::keep_largest(worst, std::abs(w[size_t(j) * g.nx() + i] - exact(g.xc(i))));
        test::keep_largest(radial, std::abs(u[size_t(j) * g.nx() + i]));
      }
  MPI_Bcast(&worst, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  MPI_Bcast(&radial, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  std::printf("pipe flow, %s wall gradient, %d radial cells: max |w - w_exact| / w(0) = %.3e, max |u_r| = %.1e\n", wall_gradient, nr, worst / exact(0),
              radial);
  EXPECT_LT(radial, 1e-10 * exact(0));
  return worst / exact(0);
}

TEST(PipeFlow, HagenPoiseuilleSecondOrder) {
  const double coarse = pipe_error(32), fine = pipe_error(128);
  const double order = std::log2(coarse / fine) / 2.0;
  std::printf("pipe flow: observed order %.3f between 32 and 128 radial cells\n", order);
  EXPECT_GT(order, 1.9);
  EXPECT_LT(fine, 1e-4);
}

TEST(PipeFlow, HagenPoiseuilleExactWithQuadraticWallGradient) {
  for (const int nr : {8, 32}) EXPECT_LT(pipe_error(nr, "quadratic"), 1e-11) << nr << " radial cells";  // exact: 4.4e-13
}

// Axial Couette flow in an annulus R1 < r < R2 whose inner wall slides at W: w(r) = W ln(r / R2) /
// ln(R1 / R2). No side is the axis, so both velocity components would have the same matrix but for
// the hoop stress on the radial one's diagonal; with one matrix for both (as once under the
// projection and PISO) the axial velocity took the hoop stress too and came out 4-14 % low.
double annulus_error(int nr, const char* coupling) {
  constexpr double R1 = 0.5, R2 = 1.0, W = 1.0;
  const std::string text = fmt::format(R"(
[mesh]
geometry = "axisymmetric"
cells = [{}, 2]
lower = [{}, 0.0]
upper = [{}, 0.05]
[time]
end = 1e9
dt = 0.5
adaptive = false
steady_tolerance = 1e-12
max_steps = 400
[fluid]
density = 1.0
viscosity = 0.1
[boundary]
west = {{ type = "wall", velocity = [0.0, {}] }}
east = {{ type = "wall" }}
south = {{ type = "atmosphere", pressure_kind = "static" }}
north = {{ type = "atmosphere", pressure_kind = "static" }}
[numerics]
convection = "upwind"
pressure_coupling = "{}"
outer_iterations = 4
outer_tolerance = 1e-12
[solver.momentum]
ksp_type = "preonly"
pc_type = "lu"
[solver.pressure]
ksp_type = "preonly"
pc_type = "lu"
[output]
progress_seconds = 0
)",
                                       nr, R1, R2, W, coupling);
  Simulation sim(PETSC_COMM_WORLD, parse_case(text), "");
  const RunSummary s = sim.run();
  EXPECT_TRUE(s.reached_steady_state) << s.steps << " steps";
  const Grid& g = sim.grid();
  const auto w = gather_to_root(g, sim.flow().velocity(1));
  double worst = 0.0;
  if (test::is_root())
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const double exact_w = W * std::log(g.xc(i) / R2) / std::log(R1 / R2);
        test::keep_largest(worst, std::abs(w[size_t(j) * g.nx() + i] - exact_w));
      }
  MPI_Bcast(&worst, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  std::printf("annular Couette flow, %s, %d radial cells: max |w - w_exact| / W = %.3e\n", coupling, nr, worst / W);
  return worst / W;
}

// The projection uses the momentum matrices (and caught the shared one); the coupled solve builds its
// own rows. PISO is left out: with its predictor it diverges where viscosity dominates (here mu dt /
// (rho dr^2) is 50 to 800, docs/method.md), and without one it takes thousands of steps to settle.
TEST(PipeFlow, AnnularCouetteSecondOrderUnderProjectionAndCoupledSolve) {
  for (const char* coupling : {"projection", "coupled"}) {
    const double coarse = annulus_error(16, coupling), fine = annulus_error(64, coupling);
    const double order = std::log2(coarse / fine) / 2.0;
    std::printf("annular Couette flow, %s: observed order %.3f between 16 and 64 radial cells\n", coupling, order);
    EXPECT_GT(order, 1.8) << coupling;
    EXPECT_LT(fine, 1e-3) << coupling;
  }
}

}  // namespace
}  // namespace granflow

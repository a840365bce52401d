// Order of accuracy on a manufactured steady Navier-Stokes solution whose viscosity varies smoothly
// by a factor 1e4 (or 1e8) across the domain (full stress, so the transpose term matters).
//   psi = sin^2(pi x) sin^2(pi y), u = dpsi/dy, v = -dpsi/dx (zero on all walls),
//   p = cos(pi x) cos(pi y), mu = 10^(D (x + y) / 2) with D decades of contrast, rho = 1,
//   f = rho (v.grad) v - div(mu (grad v + grad v^T)) + grad p.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "manufactured_run.hpp"

namespace granflow {
namespace {

constexpr double pi = std::numbers::pi;
double u_exact(double x, double y) { return pi * std::pow(std::sin(pi * x), 2) * std::sin(2 * pi * y); }
double v_exact(double x, double y) { return -pi * std::sin(2 * pi * x) * std::pow(std::sin(pi * y), 2); }
double p_exact(double x, double y) { return std::cos(pi * x) * std::cos(pi * y); }
// Decades of viscosity contrast between the corners (0, 0) and (1, 1); a test that changes it puts it back.
double contrast_decades = 4.0;
double viscosity_scale = 1.0;  // the viscosity at (0, 0); below 1 convection sets the error
double mu_exact(double x, double y) { return viscosity_scale * std::pow(10.0, 0.5 * contrast_decades * (x + y)); }
double ux(double x, double y) { return pi * pi * std::sin(2 * pi * x) * std::sin(2 * pi * y); }
double uy(double x, double y) { return 2 * pi * pi * std::pow(std::sin(pi * x), 2) * std::cos(2 * pi * y); }
double vx(double x, double y) { return -2 * pi * pi * std::cos(2 * pi * x) * std::pow(std::sin(pi * y), 2); }
double vy(double x, double y) { return -ux(x, y); }

// Stress components and their divergence by central differences of the analytic stress (h^2 error
// far below the discretisation error measured).
// full_stress false: the stress mu grad v without its transpose (numerics.transpose_stress = false),
// whose momentum rows are div(mu grad u) and div(mu grad v), txy then being u's and tyx v's.
bool full_stress = true;
double txx(double x, double y) { return (full_stress ? 2 : 1) * mu_exact(x, y) * ux(x, y); }
double txy(double x, double y) { return mu_exact(x, y) * (uy(x, y) + (full_stress ? vx(x, y) : 0.0)); }
double tyx(double x, double y) { return mu_exact(x, y) * (vx(x, y) + (full_stress ? uy(x, y) : 0.0)); }
double tyy(double x, double y) { return (full_stress ? 2 : 1) * mu_exact(x, y) * vy(x, y); }
constexpr double h = 1e-5;
double fx(double x, double y) {
  const double div = (txx(x + h, y) - txx(x - h, y)) / (2 * h) + (txy(x, y + h) - txy(x, y - h)) / (2 * h);
  const double conv = u_exact(x, y) * ux(x, y) + v_exact(x, y) * uy(x, y);
  return conv - div - pi * std::sin(pi * x) * std::cos(pi * y);
}
double fy(double x, double y) {
  const double div = (tyx(x + h, y) - tyx(x - h, y)) / (2 * h) + (tyy(x, y + h) - tyy(x, y - h)) / (2 * h);
  const double conv = u_exact(x, y) * vx(x, y) + v_exact(x, y) * vy(x, y);
  return conv - div - pi * std::cos(pi * x) * std::sin(pi * y);
}

// mesh_extra and numerics_extra: further lines of [mesh] and [numerics].
struct Stepping {
  std::string convection = "central";
  double dt = 2e-3;
};
test::VelocityPressureErrors solve_on(int n, const std::string& mesh_extra = "", const std::string& numerics_extra = "",
                                      const Stepping& stepping = {}) {
  const std::string text = fmt::format(R"(
[mesh]
cells = [{0}, {0}]
upper = [1.0, 1.0]
{1}
[time]
end = 1e6
dt = {3}
adaptive = false
steady_tolerance = 1e-9
max_steps = 20000
[fluid]
density = 1.0
viscosity = 1.0
[boundary]
west = {{ type = "wall" }}
east = {{ type = "wall" }}
south = {{ type = "wall" }}
north = {{ type = "wall" }}
[numerics]
convection = "{4}"
outer_iterations = 1
pressure_correctors = 2
{2}
[solver.momentum]
pc_type = "hypre"
[output]
progress_seconds = 0
)",
                                       n, mesh_extra, numerics_extra, stepping.dt, stepping.convection);
  return test::run_manufactured(text, {mu_exact, fx, fy, u_exact, v_exact, p_exact});
}

TEST(ManufacturedSolution, SecondOrderWithViscosityContrast1e4) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k]);
  test::expect_second_order("manufactured", sizes, e, "u", "v");
}

// The coupled solve of velocity and pressure (the granular collapses' solver, one LU per outer
// iteration) at the contrast of a soil at rest next to air: 1e8. The pressure reaches second order on
// the finer meshes (1.74, then 1.91); on 16 cells it is 1.28 from 16 to 32.
TEST(ManufacturedSolution, CoupledSolveSecondOrderWithViscosityContrast1e8) {
  const int sizes[3] = {32, 64, 128};
  test::VelocityPressureErrors e[3];
  contrast_decades = 8.0;
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k], "", "pressure_coupling = \"coupled\"");
  contrast_decades = 4.0;
  test::expect_second_order("coupled, contrast 1e8", sizes, e, "u", "v");
}

// The convection schemes' order where convection sets the error: viscosity 0.02 everywhere (a Reynolds
// number of some 150 on the velocity's scale pi), where the tests above, at a viscosity of 1 and more,
// cannot tell upwind from QUICK. Central and QUICK are second order (QUICK's face value is third order
// on uniform cells, the centred flux second); upwind is first order, and must be seen to be, or the test
// could not tell; so is the blended scheme ([VoF]'s 70 % central), by its upwind share. Measured (u, 16-32-64
// cells): central 2.01, 2.01; QUICK 2.46, 2.46; upwind 0.38, 0.53; blended 0.54, 0.74 (L2 error 0.126
// at 64 cells against central's 1.0e-3). Coupled solve, long steps to the steady state (backward Euler's
// is the discrete steady solution whatever the step); about 17 s.
TEST(ManufacturedSolution, ConvectionSchemesOrderWhereConvectionDominates) {
  const int sizes[3] = {16, 32, 64};
  contrast_decades = 0.0;
  viscosity_scale = 0.02;
  double order[4][2] = {};  // per scheme: the lesser of u's and v's, from 16 to 32 and from 32 to 64
  const char* schemes[4] = {"central", "quick", "upwind", "blended"};
  for (int s = 0; s < 4; ++s) {
    test::VelocityPressureErrors e[3];
    for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k], "", "pressure_coupling = \"coupled\"", {schemes[s], 0.2});
    for (int k = 1; k < 3; ++k) {
      const double ou = std::log2(e[k - 1].u / e[k].u), ov = std::log2(e[k - 1].v / e[k].v);
      std::printf("convection %s, viscosity 0.02: L2 u %.3e -> %.3e, order u %.2f v %.2f\n", schemes[s], e[k - 1].u,
                  e[k].u, ou, ov);
      order[s][k - 1] = std::min(ou, ov);
    }
  }
  contrast_decades = 4.0;
  viscosity_scale = 1.0;
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(order[0][k], 1.8) << "central";
    EXPECT_GE(order[1][k], 1.8) << "quick";
  }
  EXPECT_LT(order[2][1], 1.3) << "upwind";
  EXPECT_LT(order[3][1], 1.3) << "blended";  // its 30 % of upwind keeps it first order
}

// Without the transpose part of the stress (numerics.transpose_stress = false, the Laplacian form, exact
// only for a constant viscosity): against the forcing of that form, still second order.
TEST(ManufacturedSolution, CoupledSolveSecondOrderWithoutTheTransposeStress) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  full_stress = false;
  for (int k = 0; k < 3; ++k)
    e[k] = solve_on(sizes[k], "", "pressure_coupling = \"coupled\"\ntranspose_stress = false");
  full_stress = true;
  test::expect_second_order("coupled, no transpose stress", sizes, e, "u", "v");
}

// PISO without the momentum predictor (numerics.momentum_predictor = false: the pressure correctors
// start from the last velocity), at a constant viscosity: the same steady solution, second order. That
// the key takes effect shows in the steps to get there: the correctors alone relax the viscous terms
// as a Jacobi sweep would, and took 1942 steps on 32 cells against the predictor's 734.
TEST(ManufacturedSolution, PisoWithoutMomentumPredictorSecondOrder) {
  const int sizes[3] = {8, 16, 32};
  test::VelocityPressureErrors e[3];
  contrast_decades = 0.0;
  for (int k = 0; k < 3; ++k)
    e[k] = solve_on(sizes[k], "", "pressure_coupling = \"piso\"\nmomentum_predictor = false");
  const auto predicted = solve_on(sizes[2], "", "pressure_coupling = \"piso\"");
  contrast_decades = 4.0;
  test::expect_second_order("PISO without predictor", sizes, e, "u", "v");
  std::printf("PISO without predictor: %ld, %ld, %ld steps; with it on %d cells %ld\n", e[0].steps, e[1].steps,
              e[2].steps, sizes[2], predicted.steps);
  EXPECT_GT(e[2].steps, 2 * predicted.steps);
  EXPECT_NEAR(e[2].u, predicted.u, 1e-3 * predicted.u);  // the same steady solution
}

// Graded cells: widths growing 3-fold from west to east and halving from south to north (the same
// grading on every mesh, so neighbouring cells differ by 7 % on 16 cells and 1.7 % on 64).
TEST(ManufacturedSolution, CoupledSolveSecondOrderOnAGradedMesh) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k], "grading = [3.0, 0.5]", "pressure_coupling = \"coupled\"");
  test::expect_second_order("coupled, graded", sizes, e, "u", "v");
}

// The projection on the same graded mesh: the velocity is second order, the pressure only about 1.2-1.3
// (1.45-1.65 with dt = 2e-4). Its steady state depends on dt, since the Rhie-Chow term of the
// incremental projection is scaled by dt / rho (docs/method.md), and on graded cells that term's
// error falls more slowly than the discretisation's. The granular cases use the coupled solve (above).
// Not in the suite (about a minute, most of it the 64-cell run to steady state); run it with
// --gtest_also_run_disabled_tests --gtest_filter='ManufacturedSolution.*Projection*'.
TEST(ManufacturedSolution, DISABLED_ProjectionOnAGradedMeshVelocitySecondOrderPressureFirst) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k], "grading = [3.0, 0.5]");
  for (int k = 1; k < 3; ++k) {
    const double ou = std::log2(e[k - 1].u / e[k].u), ov = std::log2(e[k - 1].v / e[k].v),
                 op = std::log2(e[k - 1].p / e[k].p);
    std::printf("projection, graded, observed order %d -> %d: u %.2f  v %.2f  p %.2f\n", sizes[k - 1], sizes[k], ou, ov, op);
    EXPECT_GE(ou, 1.75);
    EXPECT_GE(ov, 1.75);
    EXPECT_GE(op, 1.1);
  }
}

}  // namespace
}  // namespace granflow

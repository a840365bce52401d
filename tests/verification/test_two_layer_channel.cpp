// Two-layer channel flow with a viscosity jump of 1e8 at mid-height: Couette (moving top wall) and
// pressure-driven (fixed static pressures at inlet and outlet), against the piecewise analytic
// profiles. The jump sits on a face, where the harmonic face viscosity makes the shear stress
// continuous. Relative error = max |u - u_exact| / max |u_exact| over cell centres.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double H = 1.0, h = 0.5, L = 0.01;          // channel height, interface height, length
constexpr double mu_soft = 1.0, mu_stiff = 1e8;       // lower and upper layer
double viscosity(double y) { return y < h ? mu_soft : mu_stiff; }

// -d/dy(mu du/dy) = G, u(0) = 0, u(H) = U, mu du/dy continuous at h.
double exact(double y, double G, double U) {
  // mu u' = -G y + C  =>  u(y) = int_0^y (-G s + C)/mu(s) ds; C from u(H) = U.
  auto integral = [&](double y1, double C) {
    const double a = std::min(y1, h), b = std::max(y1, h);
    double v = (-G * a * a / 2 + C * a) / mu_soft;
    if (y1 > h) v += (-G * (b * b - h * h) / 2 + C * (b - h)) / mu_stiff;
    return v;
  };
  const double i0 = integral(H, 0.0), i1 = integral(H, 1.0) - i0;  // u(H) = i0 + C i1
  return integral(y, (U - i0) / i1);
}

double relative_error(double G, double U, int ny, const char* face_viscosity = "harmonic") {
  const std::string text = fmt::format(R"(
[mesh]
cells = [2, {}]
upper = [{}, {}]
[time]
end = 1e9
dt = 1.0
adaptive = false
steady_tolerance = 1e-12
max_steps = 400
[fluid]
density = 1.0
viscosity = 1.0
[boundary]
west = {{ type = "atmosphere", pressure = {}, pressure_kind = "static" }}
east = {{ type = "atmosphere", pressure = 0.0, pressure_kind = "static" }}
south = {{ type = "wall" }}
north = {{ type = "wall", velocity = [{}, 0.0] }}
[numerics]
convection = "upwind"
outer_iterations = 4
outer_tolerance = 1e-12
face_viscosity = "{}"
[solver.momentum]
ksp_type = "preonly"
pc_type = "lu"
[solver.pressure]
ksp_type = "preonly"
pc_type = "lu"
[output]
progress_seconds = 0
)",
                                       ny, L, H, G * L, U, face_viscosity);
  CaseConfig config = parse_case(text);
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const Grid& g = sim.grid();
  sim.flow().set_property_update([&g](FlowSolver& f) {
    VecSet(f.density().global(), 1.0);
    test::fill(g, f.viscosity(), [](double, double y) { return viscosity(y); });
  });
  const RunSummary s = sim.run();
  EXPECT_TRUE(s.reached_steady_state) << s.steps << " steps";
  double scale = 0.0;
  for (int j = 0; j < ny; ++j) test::keep_largest(scale, std::abs(exact(g.yc(j), G, U)));
  const double err = test::l2_error(g, sim.flow().velocity(0), [&](double, double y) { return exact(y, G, U); });
  // Largest deviation: gather u and compare at every centre.
  const auto u = gather_to_root(g, sim.flow().velocity(0));
  double worst = 0.0;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < g.nx(); ++i) test::keep_largest(worst, std::abs(u[size_t(j) * g.nx() + i] - exact(g.yc(j), G, U)));
  MPI_Bcast(&worst, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  std::printf("two-layer channel G = %g, U = %g, %d cells: max error / max |u| = %.3e (L2 %.3e)\n", G, U, ny,
              worst / scale, err / scale);
  return worst / scale;
}

TEST(TwoLayerChannel, CouetteWithViscosityJump1e8) { EXPECT_LT(relative_error(0.0, 1.0, 64), 1e-10); }  // exact for a jump at a face: 1.2e-12

// The arithmetic face viscosity (numerics.face_viscosity = "arithmetic") gives the face on the jump the
// stiff layer's 5e7: the soft layer shears over half a cell less, h - dy/2 in place of h, and its top
// cell, at h - dy/2, moves with the wall (u = U) instead of at U (h - dy/2) / h: an error of U dy / (2 h)
// = U dy, first order. Measured 1.56e-2 and 7.8e-3 (= dy) on 64 and 128 cells.
TEST(TwoLayerChannel, CouetteArithmeticFaceViscosityShortensTheSoftLayerByHalfACell) {
  for (const int ny : {64, 128}) {
    const double dy = H / ny;
    EXPECT_NEAR(relative_error(0.0, 1.0, ny, "arithmetic"), dy, 0.05 * dy) << ny << " cells";
  }
}

TEST(TwoLayerChannel, PressureDrivenWithViscosityJump1e8) {
  const double coarse = relative_error(8.0, 0.0, 512);
  const double fine = relative_error(8.0, 0.0, 2048);
  EXPECT_GT(std::log2(coarse / fine) / 2.0, 1.9);  // second order
  EXPECT_LT(fine, 1e-6);
}

}  // namespace
}  // namespace granflow

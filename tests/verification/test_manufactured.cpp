// Order of accuracy on a manufactured steady Navier-Stokes solution whose viscosity varies smoothly
// by a factor 1e4 across the domain (full stress, so the transpose term matters).
//   psi = sin^2(pi x) sin^2(pi y), u = dpsi/dy, v = -dpsi/dx (zero on all walls),
//   p = cos(pi x) cos(pi y), mu = 10^(2 (x + y)), rho = 1,
//   f = rho (v.grad) v - div(mu (grad v + grad v^T)) + grad p.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double pi = std::numbers::pi;
double u_exact(double x, double y) { return pi * std::pow(std::sin(pi * x), 2) * std::sin(2 * pi * y); }
double v_exact(double x, double y) { return -pi * std::sin(2 * pi * x) * std::pow(std::sin(pi * y), 2); }
double p_exact(double x, double y) { return std::cos(pi * x) * std::cos(pi * y); }
double mu_exact(double x, double y) { return std::pow(10.0, 2.0 * (x + y)); }
double ux(double x, double y) { return pi * pi * std::sin(2 * pi * x) * std::sin(2 * pi * y); }
double uy(double x, double y) { return 2 * pi * pi * std::pow(std::sin(pi * x), 2) * std::cos(2 * pi * y); }
double vx(double x, double y) { return -2 * pi * pi * std::cos(2 * pi * x) * std::pow(std::sin(pi * y), 2); }
double vy(double x, double y) { return -ux(x, y); }

// Stress components and their divergence by central differences of the analytic stress (h^2 error
// far below the discretisation error measured).
double txx(double x, double y) { return 2 * mu_exact(x, y) * ux(x, y); }
double txy(double x, double y) { return mu_exact(x, y) * (uy(x, y) + vx(x, y)); }
double tyy(double x, double y) { return 2 * mu_exact(x, y) * vy(x, y); }
constexpr double h = 1e-5;
double fx(double x, double y) {
  const double div = (txx(x + h, y) - txx(x - h, y)) / (2 * h) + (txy(x, y + h) - txy(x, y - h)) / (2 * h);
  const double conv = u_exact(x, y) * ux(x, y) + v_exact(x, y) * uy(x, y);
  return conv - div - pi * std::sin(pi * x) * std::cos(pi * y);
}
double fy(double x, double y) {
  const double div = (txy(x + h, y) - txy(x - h, y)) / (2 * h) + (tyy(x, y + h) - tyy(x, y - h)) / (2 * h);
  const double conv = u_exact(x, y) * vx(x, y) + v_exact(x, y) * vy(x, y);
  return conv - div - pi * std::cos(pi * x) * std::sin(pi * y);
}

struct Errors {
  double u, v, p;
};

Errors solve_on(int n) {
  const std::string text = fmt::format(R"(
[mesh]
cells = [{0}, {0}]
upper = [1.0, 1.0]
[time]
end = 1e6
dt = 2e-3
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
convection = "central"
outer_iterations = 1
pressure_correctors = 2
[solver.momentum]
pc_type = "hypre"
[output]
progress_seconds = 0
)",
                                       n);
  CaseConfig config = parse_case(text);
  Simulation sim(PETSC_COMM_WORLD, config, "");
  FlowSolver& flow = sim.flow();
  const Grid& g = sim.grid();
  flow.set_property_update([&g](FlowSolver& f) {
    VecSet(f.density().global(), 1.0);
    test::fill(g, f.viscosity(), mu_exact);
  });
  flow.enable_body_force();
  test::fill(g, flow.body_force(0), fx);
  test::fill(g, flow.body_force(1), fy);
  const RunSummary s = sim.run();
  EXPECT_TRUE(s.reached_steady_state) << n << " cells: not steady after " << s.steps << " steps";
  return {test::l2_error(g, flow.velocity(0), u_exact), test::l2_error(g, flow.velocity(1), v_exact),
          test::l2_error(g, flow.pressure(), p_exact, true)};
}

TEST(ManufacturedSolution, SecondOrderWithViscosityContrast1e4) {
  const int sizes[3] = {16, 32, 64};
  Errors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k]);
  for (int k = 0; k < 3; ++k)
    std::printf("manufactured n = %3d: L2 error u %.3e  v %.3e  p %.3e\n", sizes[k], e[k].u, e[k].v, e[k].p);
  for (int k = 1; k < 3; ++k) {
    const double ou = std::log2(e[k - 1].u / e[k].u), ov = std::log2(e[k - 1].v / e[k].v),
                 op = std::log2(e[k - 1].p / e[k].p);
    std::printf("observed order %d -> %d: u %.2f  v %.2f  p %.2f\n", sizes[k - 1], sizes[k], ou, ov, op);
    EXPECT_GE(ou, 1.8);
    EXPECT_GE(ov, 1.8);
    EXPECT_GE(op, 1.5);
  }
}

}  // namespace
}  // namespace granflow

// Order of accuracy on a manufactured steady Navier-Stokes solution whose viscosity varies smoothly
// by a factor 1e4 across the domain (full stress, so the transpose term matters).
//   psi = sin^2(pi x) sin^2(pi y), u = dpsi/dy, v = -dpsi/dx (zero on all walls),
//   p = cos(pi x) cos(pi y), mu = 10^(2 (x + y)), rho = 1,
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

test::VelocityPressureErrors solve_on(int n) {
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
  return test::run_manufactured(text, {mu_exact, fx, fy, u_exact, v_exact, p_exact});
}

TEST(ManufacturedSolution, SecondOrderWithViscosityContrast1e4) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k]);
  test::expect_second_order("manufactured", sizes, e, "u", "v");
}

}  // namespace
}  // namespace granflow

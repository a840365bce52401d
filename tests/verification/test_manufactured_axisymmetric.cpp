// Order of accuracy of the axisymmetric (r-z) discretisation on a manufactured steady solution with
// a viscosity varying by a factor 100: the area- and volume-weighted fluxes, the full stress and the
// hoop stress 2 mu u_r / r^2 all enter. From the stream function psi = r^2 (1 - r^2)^2 sin^2(pi z):
//   u_r = -(1/r) dpsi/dz = -r (1 - r^2)^2 pi sin(2 pi z),
//   u_z =  (1/r) dpsi/dr = 2 (1 - r^2)(1 - 3 r^2) sin^2(pi z),
// divergence-free, zero on the walls r = 1, z = 0 and z = 1, u_r odd and u_z even in r (smooth on the
// axis); p = cos(pi r) cos(pi z), mu = 10^(r + z), rho = 1;
//   f = rho (v.grad) v + grad p - div(2 mu D),
//   div(2 mu D)_r = (1/r) d(r tau_rr)/dr + d tau_rz/dz - tau_tt / r,  tau_tt = 2 mu u_r / r,
//   div(2 mu D)_z = (1/r) d(r tau_rz)/dr + d tau_zz/dz.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "manufactured_run.hpp"

namespace granflow {
namespace {

constexpr double pi = std::numbers::pi;
double ur(double r, double z) { return -r * std::pow(1 - r * r, 2) * pi * std::sin(2 * pi * z); }
double uz(double r, double z) { return 2 * (1 - r * r) * (1 - 3 * r * r) * std::pow(std::sin(pi * z), 2); }
double p_exact(double r, double z) { return std::cos(pi * r) * std::cos(pi * z); }
double mu_exact(double r, double z) { return std::pow(10.0, r + z); }

// Derivatives by central differences of the analytic fields (h^2 ~ 1e-8, far below the errors measured).
constexpr double h = 1e-4;
template <class F>
double d_r(F f, double r, double z) { return (f(r + h, z) - f(r - h, z)) / (2 * h); }
template <class F>
double d_z(F f, double r, double z) { return (f(r, z + h) - f(r, z - h)) / (2 * h); }

double r_trr(double r, double z) { return r * 2 * mu_exact(r, z) * d_r(ur, r, z); }
double trz(double r, double z) { return mu_exact(r, z) * (d_z(ur, r, z) + d_r(uz, r, z)); }
double r_trz(double r, double z) { return r * trz(r, z); }
double tzz(double r, double z) { return 2 * mu_exact(r, z) * d_z(uz, r, z); }

double force_r(double r, double z) {
  const double div = d_r(r_trr, r, z) / r + d_z(trz, r, z) - 2 * mu_exact(r, z) * ur(r, z) / (r * r);
  const double conv = ur(r, z) * d_r(ur, r, z) + uz(r, z) * d_z(ur, r, z);
  return conv + d_r(p_exact, r, z) - div;
}
double force_z(double r, double z) {
  const double div = d_r(r_trz, r, z) / r + d_z(tzz, r, z);
  const double conv = ur(r, z) * d_r(uz, r, z) + uz(r, z) * d_z(uz, r, z);
  return conv + d_z(p_exact, r, z) - div;
}

// Without the transposed gradient (numerics.transpose_stress = false) the viscous term is div(mu grad v),
// whose radial component has the hoop term -mu u_r / r^2, half the full stress's:
//   div(mu grad v)_r = (1/r) d(r mu du_r/dr)/dr + d(mu du_r/dz)/dz - mu u_r / r^2,
//   div(mu grad v)_z = (1/r) d(r mu du_z/dr)/dr + d(mu du_z/dz)/dz.
double r_mu_dur_dr(double r, double z) { return r * mu_exact(r, z) * d_r(ur, r, z); }
double mu_dur_dz(double r, double z) { return mu_exact(r, z) * d_z(ur, r, z); }
double r_mu_duz_dr(double r, double z) { return r * mu_exact(r, z) * d_r(uz, r, z); }
double mu_duz_dz(double r, double z) { return mu_exact(r, z) * d_z(uz, r, z); }
double force_r_without_transpose(double r, double z) {
  const double div = d_r(r_mu_dur_dr, r, z) / r + d_z(mu_dur_dz, r, z) - mu_exact(r, z) * ur(r, z) / (r * r);
  const double conv = ur(r, z) * d_r(ur, r, z) + uz(r, z) * d_z(ur, r, z);
  return conv + d_r(p_exact, r, z) - div;
}
double force_z_without_transpose(double r, double z) {
  const double div = d_r(r_mu_duz_dr, r, z) / r + d_z(mu_duz_dz, r, z);
  const double conv = ur(r, z) * d_r(uz, r, z) + uz(r, z) * d_z(uz, r, z);
  return conv + d_z(p_exact, r, z) - div;
}

// numerics_extra: further lines of [numerics].
test::VelocityPressureErrors solve_on(int n, const std::string& numerics_extra = "", bool transpose_stress = true) {
  const std::string text = fmt::format(R"(
[mesh]
geometry = "axisymmetric"
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
west = {{ type = "axis" }}
east = {{ type = "wall" }}
south = {{ type = "wall" }}
north = {{ type = "wall" }}
[numerics]
convection = "central"
outer_iterations = 1
{1}
[solver.momentum]
pc_type = "hypre"
[output]
progress_seconds = 0
)",
                                       n, numerics_extra);
  if (!transpose_stress)
    return test::run_manufactured(text, {mu_exact, force_r_without_transpose, force_z_without_transpose, ur, uz, p_exact});
  return test::run_manufactured(text, {mu_exact, force_r, force_z, ur, uz, p_exact});
}

TEST(ManufacturedSolution, AxisymmetricSecondOrderWithViscosityContrast100) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k]);
  test::expect_second_order("axisymmetric manufactured", sizes, e, "u_r", "u_z");
}

// The coupled solve of velocity and pressure, as the axisymmetric collapses of [YS] Sec. 4 use it.
TEST(ManufacturedSolution, AxisymmetricCoupledSolveSecondOrder) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k], "pressure_coupling = \"coupled\"");
  test::expect_second_order("axisymmetric, coupled", sizes, e, "u_r", "u_z");
}

// div(mu grad v) alone (numerics.transpose_stress = false): its own, smaller hoop term. With the full
// stress's 2 mu u_r / r^2 in its place (as before) the errors stayed near 2e-2 and did not fall.
TEST(ManufacturedSolution, AxisymmetricWithoutTransposedGradientSecondOrder) {
  const int sizes[3] = {16, 32, 64};
  test::VelocityPressureErrors e[3];
  for (int k = 0; k < 3; ++k) e[k] = solve_on(sizes[k], "pressure_coupling = \"coupled\"\ntranspose_stress = false", false);
  test::expect_second_order("axisymmetric, without the transposed gradient", sizes, e, "u_r", "u_z");
}

}  // namespace
}  // namespace granflow

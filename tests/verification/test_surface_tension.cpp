// Surface tension (soil.surface_tension, solver/surface_tension_force.hpp) against the two classical
// results for a drop of water in air without gravity:
//   - Laplace's law: at rest the pressure inside exceeds the air's by sigma / R for a cylinder (planar
//     mesh), 2 sigma / R for a sphere (axisymmetric mesh, and a mesh of layers);
//   - Rayleigh's oscillation: a drop deformed in its second mode oscillates with
//     omega^2 = n (n^2 - 1) sigma / ((rho_in + rho_out) R^3), n = 2, for a cylinder (Lamb, Hydrodynamics,
//     Sec. 275, with both phases' inertia).
// The measured numbers of each are printed and in docs/validation.md ("Surface tension").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double sigma = 0.072, radius = 0.004;

// A water drop of radius 4 mm at the centre of a closed 2 x 2 cm box without gravity.
std::string drop_case(const std::string& mesh, const std::string& shape, const std::string& extra_sides = "") {
  return R"(
title = "drop at rest"
)" + mesh +
         R"(
[time]
end = 0.01
dt = 1e-5
courant = 0.25
[air]
density = 1.0
viscosity = 1.8e-5
[soil]
density = 1000.0
viscosity = 1e-3
surface_tension = 0.072
[mixture]
density = "linear"
viscosity = "linear"
[[initial.soil]]
)" + shape +
         R"(
[boundary]
south = { type = "wall" }
east = { type = "wall" }
north = { type = "wall" }
)" + extra_sides +
         R"(
[output]
fields = false
progress_seconds = 0
)";
}

std::string planar_mesh(int n) {
  return "[mesh]\ncells = [" + std::to_string(n) + ", " + std::to_string(n) +
         "]\nupper = [0.02, 0.02]\n[physics]\ngravity = [0.0, 0.0]";
}
const std::string planar_drop = "shape = \"circle\"\ncentre = [0.01, 0.01]\nradius = 0.004";

struct DropAtRest {
  double pressure_jump = 0.0;  // mean pressure of the cells of water less that of the cells of air, Pa
  double largest_speed = 0.0;  // m/s, the spurious currents
  double volume_drift = 0.0;   // relative
};

DropAtRest run_drop(const CaseConfig& config) {
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const RunSummary s = sim.run();
  const Grid& g = sim.grid();
  const std::vector<double> p = gather_to_all(g, sim.flow().pressure());
  const std::vector<double> c = gather_to_all(g, sim.soil()->soil_fraction());
  double sums[4] = {0, 0, 0, 0};  // water p, water cells, air p, air cells
  for (size_t n = 0; n < p.size(); ++n) {
    if (c[n] > 0.999) sums[0] += p[n], sums[1] += 1;
    if (c[n] < 0.001) sums[2] += p[n], sums[3] += 1;
  }
  DropAtRest d;
  d.pressure_jump = sums[0] / sums[1] - sums[2] / sums[3];
  d.largest_speed = sim.flow().max_speed();
  d.volume_drift = std::abs(s.soil_volume_error);
  return d;
}

// The cylinder's jump sigma / R = 18 Pa on 20 x 20 and 40 x 40 cells (R = 4 and 8 cells): measured
// 6.3 % and 3.2 % above it, the spurious currents below 0.02 m/s (capillary number mu u / sigma < 3e-4).
TEST(SurfaceTension, PlanarDropHoldsLaplacesPressure) {
  double error[2];
  for (int level = 0; level < 2; ++level) {
    const int n = 20 << level;
    const DropAtRest d = run_drop(parse_case(drop_case(planar_mesh(n), planar_drop, "west = { type = \"wall\" }")));
    error[level] = std::abs(d.pressure_jump / (sigma / radius) - 1.0);
    if (test::is_root())
      std::printf("planar drop, %d x %d: jump %.4f Pa (sigma / R = %.4f), error %.4f, largest speed %.3g m/s\n", n, n,
                  d.pressure_jump, sigma / radius, error[level], d.largest_speed);
    EXPECT_LT(d.largest_speed, 0.03);
    EXPECT_LT(d.volume_drift, 1e-12);
  }
  EXPECT_LT(error[0], 0.08);
  EXPECT_LT(error[1], 0.045);
  EXPECT_LT(error[1], 0.7 * error[0]);  // falls with the mesh
}

// The history's surface_energy, sigma times the integral of |grad c~|, is sigma 2 pi R for the resting
// drop (measured 0.96 % below on 40 x 40 cells). What the spurious currents take from the force shows in
// the budget: kinetic + dissipated + surface energy grows by 1.0 % of the surface energy over 0.15 s.
TEST(SurfaceTension, HistoryCountsTheInterfaceEnergy) {
  const auto out = test::scratch("surface_energy");
  {
    Simulation sim(PETSC_COMM_WORLD,
                   parse_case(drop_case(planar_mesh(40), planar_drop, "west = { type = \"wall\" }"), {"time.end=0.15"}),
                   out);
    sim.run();
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  auto h = test::read_csv((out / "history.csv").string());
  MPI_Barrier(PETSC_COMM_WORLD);
  test::remove_scratch(out);
  ASSERT_TRUE(h.count("surface_energy"));
  const auto& S = h["surface_energy"];
  const double exact = sigma * 2 * std::numbers::pi * radius;
  const double gain = h["kinetic_energy"].back() + h["dissipated_energy"].back() + S.back() - S.front();
  if (test::is_root())
    std::printf("resting drop: surface energy %.6g J/m (sigma 2 pi R = %.6g), budget's gain by t = 0.15 s %.3g of it\n",
                S.front(), exact, gain / S.front());
  EXPECT_NEAR(S.front() / exact, 1.0, 0.02);
  EXPECT_LT(std::abs(S.back() / S.front() - 1.0), 1e-3);  // the drop keeps its shape
  EXPECT_LT(gain, 0.02 * S.front());
}

// The same drop under each pressure coupling: the face source enters each alike.
TEST(SurfaceTension, EveryPressureCouplingBalancesIt) {
  for (const char* coupling : {"coupled", "piso"}) {
    const DropAtRest d = run_drop(parse_case(drop_case(planar_mesh(40), planar_drop, "west = { type = \"wall\" }"),
                                             {std::string("numerics.pressure_coupling=") + coupling}));
    const double error = std::abs(d.pressure_jump / (sigma / radius) - 1.0);
    if (test::is_root())
      std::printf("%s: jump %.4f Pa, error %.4f, largest speed %.3g m/s\n", coupling, d.pressure_jump, error,
                  d.largest_speed);
    EXPECT_LT(error, 0.045) << coupling;
    EXPECT_LT(d.largest_speed, 0.08) << coupling;
  }
}

// A sphere: on an axisymmetric mesh (the drop's centre on the axis, 20 x 40 cells of 0.5 mm) the hoop
// curvature comes from the faces' radii; the jump is 2 sigma / R = 36 Pa (measured 2.4 % above).
TEST(SurfaceTension, AxisymmetricDropHoldsLaplacesPressure) {
  const std::string mesh =
      "[mesh]\ncells = [20, 40]\nupper = [0.01, 0.02]\ngeometry = \"axisymmetric\"\n"
      "[physics]\ngravity = [0.0, 0.0]";
  const DropAtRest d = run_drop(parse_case(
      drop_case(mesh, "shape = \"circle\"\ncentre = [0.0, 0.01]\nradius = 0.004", "west = { type = \"axis\" }")));
  const double error = std::abs(d.pressure_jump / (2 * sigma / radius) - 1.0);
  if (test::is_root())
    std::printf("axisymmetric drop: jump %.4f Pa (2 sigma / R = %.4f), error %.4f\n", d.pressure_jump,
                2 * sigma / radius, error);
  EXPECT_LT(error, 0.045);
  EXPECT_LT(d.largest_speed, 0.03);
}

// A sphere on a mesh of layers, 24 x 24 x 24 cells (R = 4.8 cells), to t = 5 ms: 2 sigma / R (measured
// 5.1 % above).
TEST(SurfaceTension, DropOnAMeshOfLayersHoldsLaplacesPressure) {
  const std::string mesh =
      "[mesh]\ncells = [24, 24, 24]\nupper = [0.02, 0.02, 0.02]\n[physics]\ngravity = [0.0, 0.0, 0.0]";
  const DropAtRest d = run_drop(
      parse_case(drop_case(mesh, "shape = \"sphere\"\ncentre = [0.01, 0.01, 0.01]\nradius = 0.004",
                           "west = { type = \"wall\" }\nfront = { type = \"wall\" }\nback = { type = \"wall\" }"),
                 {"time.end=0.005"}));
  const double error = std::abs(d.pressure_jump / (2 * sigma / radius) - 1.0);
  if (test::is_root())
    std::printf("drop on layers: jump %.4f Pa (2 sigma / R = %.4f), error %.4f\n", d.pressure_jump, 2 * sigma / radius,
                error);
  EXPECT_LT(error, 0.07);
  EXPECT_LT(d.largest_speed, 0.03);
}

// A drop on the floor: a half disc of radius 3 mm without gravity, 40 x 20 cells of 0.5 mm, a viscous
// liquid (0.05 Pa s) so that it settles by t = 0.1 s. At the contact angle theta it takes the shape of a
// circular cap of the same area: its angle, read as 2 atan(h / b) from its height h at the centre and
// its half base b (both from sums of c), is theta's. Measured: 61.8 deg for 60, 116.3 deg for 120
// (61.4 and 117.7 on 80 x 40 cells; a right angle gives 90.2 there).
TEST(SurfaceTension, ADropOnTheFloorTakesItsContactAngle) {
  const std::string mesh = "[mesh]\ncells = [40, 20]\nupper = [0.02, 0.01]\n[physics]\ngravity = [0.0, 0.0]";
  for (double theta : {60.0, 120.0}) {
    Simulation sim(PETSC_COMM_WORLD,
                   parse_case(drop_case(mesh, "shape = \"circle\"\ncentre = [0.01, 0.0]\nradius = 0.003",
                                        "west = { type = \"wall\" }"),
                              {"time.end=0.1", "soil.viscosity=0.05", "soil.contact_angle=" + std::to_string(theta)}),
                   "");
    sim.run();
    const Grid& g = sim.grid();
    const std::vector<double> c = gather_to_all(g, sim.soil()->soil_fraction());
    const double dx = g.dx(0), dy = g.dy(0);
    double base = 0.0, height = 0.0;
    for (int i = 0; i < g.nx(); ++i) base += c[size_t(i)] * dx / 2;  // the floor's row
    for (int j = 0; j < g.ny(); ++j)                                 // the two columns at the centre
      height += 0.5 * (c[size_t(j) * g.nx() + g.nx() / 2 - 1] + c[size_t(j) * g.nx() + g.nx() / 2]) * dy;
    const double angle = 2 * std::atan(height / base) * 180 / std::numbers::pi;
    // The cap of the half disc's area pi r^2 / 2 at theta: R^2 (theta - sin theta cos theta) = area.
    const double t = theta * std::numbers::pi / 180;
    const double R = std::sqrt(std::numbers::pi * 0.003 * 0.003 / 2 / (t - std::sin(t) * std::cos(t)));
    if (test::is_root())
      std::printf("drop on the floor at %.0f deg: apparent angle %.1f deg, height %.3f mm (cap %.3f mm)\n", theta,
                  angle, height * 1e3, R * (1 - std::cos(t)) * 1e3);
    EXPECT_NEAR(angle, theta, 5.0);
    EXPECT_NEAR(height, R * (1 - std::cos(t)), 0.05 * R * (1 - std::cos(t)));
  }
}

// The force is explicit: every step, a fixed one too, is at most the capillary limit
// sqrt((rho_w + rho_a) h^3 / (4 pi sigma)) = 1.05e-3 s on cells of 1 mm, though time.dt asks for 5e-3 s.
TEST(SurfaceTension, EveryStepIsWithinTheCapillaryLimit) {
  const double limit = std::sqrt((1000.0 + 1.0) * 1e-9 / (4 * std::numbers::pi * sigma));
  for (const char* adaptive : {"true", "false"}) {
    std::vector<double> steps;
    Simulation sim(PETSC_COMM_WORLD,
                   parse_case(drop_case(planar_mesh(20), planar_drop, "west = { type = \"wall\" }"),
                              {"time.end=0.02", "time.dt=5e-3", std::string("time.adaptive=") + adaptive}),
                   "");
    sim.run([&](Simulation&, double dt) { steps.push_back(dt); });
    ASSERT_GE(steps.size(), 19u) << adaptive;
    for (double dt : steps) EXPECT_LE(dt, limit * (1 + 1e-12)) << "adaptive = " << adaptive;
    EXPECT_NEAR(steps[1], limit, 1e-12 * limit) << "adaptive = " << adaptive;  // the drop at rest: the limit binds
  }
}

// A cylinder of water with radius R (1 + 0.1 cos 2 theta), released from rest on 40 x 40 cells, to
// t = 0.15 s (two periods): the period of its elongation, fitted as m + a cos(omega t) + b sin(omega t),
// against Rayleigh's 2 pi / omega_2 = 76.5 ms. Measured: 80.0 ms on 40 x 40, 78.6 ms on 80 x 80
// (docs/validation.md); a finite amplitude and the viscosity both lengthen it a little.
TEST(SurfaceTension, DeformedDropOscillatesAtRayleighsPeriod) {
  std::string polygon = "shape = \"polygon\"\npoints = [";
  for (int k = 0; k < 72; ++k) {
    const double theta = 2 * std::numbers::pi * k / 72, r = radius * (1 + 0.1 * std::cos(2 * theta));
    polygon += (k ? ", [" : "[") + std::to_string(0.01 + r * std::cos(theta)) + ", " +
               std::to_string(0.01 + r * std::sin(theta)) + "]";
  }
  polygon += "]";
  std::vector<double> t, width;
  {
    Simulation sim(PETSC_COMM_WORLD,
                   parse_case(drop_case(planar_mesh(40), polygon, "west = { type = \"wall\" }"), {"time.end=0.15"}),
                   "");
    // The drop's elongation along x: the integral of c ((x - x0)^2 - (y - y0)^2), its second mode's
    // amplitude times a constant.
    sim.run([&](Simulation& s, double) {
      const Grid& g = s.grid();
      const std::vector<double> c = gather_to_all(g, s.soil()->soil_fraction());
      double moment = 0.0;
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
          const double x = g.xc(i) - 0.01, y = g.yc(j) - 0.01;
          moment += c[size_t(j) * g.nx() + i] * (x * x - y * y) * g.volume(i, j);
        }
      t.push_back(s.time());
      width.push_back(moment);
    });
  }
  // Least squares of m + a cos(omega t) + b sin(omega t) over omega (a scan, then its best).
  auto residual = [&](double omega) {
    double A[3][3] = {}, r[3] = {};
    for (size_t k = 0; k < t.size(); ++k) {
      const double f[3] = {1.0, std::cos(omega * t[k]), std::sin(omega * t[k])};
      for (int i = 0; i < 3; ++i) {
        r[i] += f[i] * width[k];
        for (int j = 0; j < 3; ++j) A[i][j] += f[i] * f[j];
      }
    }
    // Solve the 3 x 3 normal equations (Cramer), then the residual sum of squares.
    auto det = [](double m[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double D = det(A);
    double x[3];
    for (int col = 0; col < 3; ++col) {
      double M[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) M[i][j] = j == col ? r[i] : A[i][j];
      x[col] = det(M) / D;
    }
    double sum = 0.0;
    for (size_t k = 0; k < t.size(); ++k) {
      const double e = x[0] + x[1] * std::cos(omega * t[k]) + x[2] * std::sin(omega * t[k]) - width[k];
      sum += e * e;
    }
    return sum;
  };
  double best_omega = 0.0, best = INFINITY;
  for (double omega = 40.0; omega <= 140.0; omega += 0.05)
    if (const double r = residual(omega); r < best) best = r, best_omega = omega;
  const double rayleigh = std::sqrt(6 * sigma / ((1000.0 + 1.0) * std::pow(radius, 3)));
  const double period = 2 * std::numbers::pi / best_omega, expected = 2 * std::numbers::pi / rayleigh;
  if (test::is_root())
    std::printf("oscillating drop: period %.5f s, Rayleigh %.5f s, ratio %.4f\n", period, expected, period / expected);
  EXPECT_NEAR(period / expected, 1.0, 0.07);
}

}  // namespace
}  // namespace granflow

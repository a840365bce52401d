// Soil materials carried with the soil (material_transport.hpp): each material's volume and the
// soil's conserved to round-off, and the material back where it started when the flow reverses, with
// an error that falls with the mesh.
#include "models/interface/material_transport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "interface_test_utils.hpp"
#include "serial_vof_field.hpp"

namespace granflow::interface {
namespace {

constexpr double kPi = std::numbers::pi;

struct MaterialRun {
  int n = 0;
  double volume_error = 0.0;     // largest |V_k - V_k0| / V_k0 over the steps and materials
  double soil_error = 0.0;       // the same for the soil's volume
  double share_min = 1.0, share_max = 0.0;
  double l1 = 0.0;               // sum |q - q0| V of the first material at t = T, q = c m
  double volume = 0.0;           // its volume
};

// A disc of radius 0.15 at (0.5, 0.75) cut in three: the left third (x < 0.45) is material 1, the top
// of the rest (y > 0.8) material 2, the remainder the base. Carried to t = T by LeVeque's reversing
// vortex (period T = 2, reversing: the exact state at T is the initial one) or a solid-body rotation
// about (0.5, 0.5) (T = 1, one revolution).
enum class Flow { reversing_vortex, rotation };

// The disc on f's n x n cells (c and both materials' shares, ghosts filled); returns the first
// material's q = c m per cell.
std::vector<double> lay_out_disc(SerialVofField& f, int n, double x_centre) {
  const auto disc = [&](double x, double y) { return test::circle_inside(x, y, x_centre, 0.75, 0.15); };
  const auto first = [&](double x, double y) { return disc(x, y) && x < x_centre - 0.05; };
  const auto second = [&](double x, double y) { return disc(x, y) && x >= x_centre - 0.05 && y > 0.8; };
  std::vector<double> q0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x0 = f.x_face(i), x1 = f.x_face(i + 1), y0 = f.y_face(j), y1 = f.y_face(j + 1);
      const double c = test::sampled_fraction(x0, x1, y0, y1, disc);
      f.c()(i, j) = c;
      f.material(0)(i, j) = c > 0.0 ? test::sampled_fraction(x0, x1, y0, y1, first) / c : 0.0;
      f.material(1)(i, j) = c > 0.0 ? test::sampled_fraction(x0, x1, y0, y1, second) / c : 0.0;
      q0.push_back(c * f.material(0)(i, j));
    }
  f.fill_ghosts();
  return q0;
}

// LeVeque's reversing vortex at its full strength (the caller scales it in time).
void set_vortex(SerialVofField& f) {
  f.set_velocity_from_stream_function([](double x, double y) {
    const double sx = std::sin(kPi * x), sy = std::sin(kPi * y);
    return sx * sx * sy * sy / kPi;
  });
}

// Axisymmetric: the same stream function as Stokes's (x = r), the disc the section of a torus.
MaterialRun run_disc(int n, Flow flow, bool axisymmetric = false, double x_centre = 0.5, double cfl = 0.4) {
  SerialVofField f(n, n, 1.0, 1.0);
  f.set_boundary(VofBoundary::Empty);
  f.set_axisymmetric(axisymmetric);
  f.track_materials(2);
  const std::vector<double> q0 = lay_out_disc(f, n, x_centre);
  if (flow == Flow::reversing_vortex)
    set_vortex(f);
  else
    f.set_velocity_from_stream_function([](double x, double y) { return -kPi * ((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)); });
  GhostedArray2 ux0(n, n, 2), uy0(n, n, 2);
  for (int j = -2; j < n + 2; ++j)
    for (int i = -2; i < n + 2; ++i) {
      ux0(i, j) = f.ux()(i, j);
      uy0(i, j) = f.uy()(i, j);
    }
  const double period = flow == Flow::reversing_vortex ? 2.0 : 1.0;
  const long steps = long(std::ceil(period * f.max_courant(1.0) / cfl));
  const double dt = period / double(steps);
  const double soil0 = f.total_volume(), v0[2] = {f.material_volume(0), f.material_volume(1)};
  MaterialRun r;
  r.n = n;
  for (long s = 0; s < steps; ++s) {
    // At mid-step: the velocity stays divergence-free.
    const double a = flow == Flow::reversing_vortex ? std::cos(kPi * (double(s) + 0.5) * dt / period) : 1.0;
    for (int j = -2; j < n + 2; ++j)
      for (int i = -2; i < n + 2; ++i) {
        f.ux()(i, j) = a * ux0(i, j);
        f.uy()(i, j) = a * uy0(i, j);
      }
    f.step(dt);
    r.soil_error = std::max(r.soil_error, std::abs(f.total_volume() - soil0) / soil0);
    for (int k = 0; k < 2; ++k) {
      r.volume_error = std::max(r.volume_error, std::abs(f.material_volume(k) - v0[k]) / v0[k]);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          if (f.c()(i, j) > 1e-9) r.share_min = std::min(r.share_min, f.material(k)(i, j));
          if (f.c()(i, j) > 1e-9) r.share_max = std::max(r.share_max, f.material(k)(i, j) + f.material(1 - k)(i, j));
        }
    }
  }
  std::size_t k = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) r.l1 += std::abs(f.c()(i, j) * f.material(0)(i, j) - q0[k++]) * f.dx()[i] * f.dy()[j];
  r.volume = v0[0];
  return r;
}

void report(const char* name, const std::vector<MaterialRun>& runs) {
  std::printf("[materials] %s, a disc cut in three materials, CFL 0.4 per sweep\n", name);
  std::printf("[materials]   %5s %12s %12s %12s %12s %12s\n", "n", "L1 / V", "max dV/V0", "soil dV/V0", "min share",
              "max sum - 1");
  for (const MaterialRun& r : runs) {
    std::printf("[materials]   %5d %12.4e %12.2e %12.2e %12.2e %12.2e\n", r.n, r.l1 / r.volume, r.volume_error,
                r.soil_error, r.share_min, r.share_max - 1.0);
    // The sweep clamps the shares to [0, 1] and their sum to 1, so their bounds say nothing; that
    // each material keeps its volume to round-off shows the clamp took nothing away.
    EXPECT_LT(r.volume_error, 1e-12) << r.n;
    EXPECT_LT(r.soil_error, 1e-12) << r.n;
  }
}

// The vortex draws the disc into a spiral thinner than a cell, where materials side by side mix for
// good: the error falls at about first order (0.66, 0.39, 0.18 of the material's volume).
TEST(MaterialTransport, ReversingVortexConservesEachMaterialAndBringsItBack) {
  std::vector<MaterialRun> runs;
  for (int n : {32, 64, 128}) runs.push_back(run_disc(n, Flow::reversing_vortex));
  report("reversing vortex T = 2", runs);
  for (std::size_t k = 1; k < runs.size(); ++k) EXPECT_LT(runs[k].l1, 0.7 * runs[k - 1].l1) << runs[k].n;
  EXPECT_LT(runs.back().l1 / runs.back().volume, 0.25);
}

// Moved whole, as most soil moves, a material comes back with its contacts a cell or two wide.
TEST(MaterialTransport, RotationConservesEachMaterialAndBringsItBack) {
  std::vector<MaterialRun> runs;
  for (int n : {32, 64, 128}) runs.push_back(run_disc(n, Flow::rotation));
  report("solid-body rotation, one revolution", runs);
  for (std::size_t k = 1; k < runs.size(); ++k) EXPECT_LT(runs[k].l1, 0.7 * runs[k - 1].l1) << runs[k].n;
}

// On an axisymmetric mesh the x sweep's fluxes and the donor's soil are radius-weighted; so must the
// soil's Courant number that bounds the face shares be, or donors near the axis give more than they
// hold and the materials' volumes drift (7e-6 of them in random flows, before). The disc reaches to
// within 0.01 of the axis; Courant number 0.45 per sweep.
TEST(MaterialTransport, AxisymmetricVortexConservesEachMaterial) {
  std::vector<MaterialRun> runs;
  for (int n : {32, 64}) runs.push_back(run_disc(n, Flow::reversing_vortex, true, 0.16, 0.45));
  report("axisymmetric reversing vortex T = 2, a torus about the axis (L1 not radius-weighted)", runs);
}

// A contact carried by a uniform flow through soil that fills the box moves with it: the material's
// centroid goes where the flow takes it, and its volume stays. A donor taken downwind would not.
TEST(MaterialTransport, ContactMovesWithTheSoil) {
  const int n = 64;
  SerialVofField f(n, 4, 1.0, 1.0 / 16.0);
  f.set_boundary(VofBoundary::Periodic);
  f.track_materials(1);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < n; ++i) {
      f.c()(i, j) = 1.0;
      f.material(0)(i, j) = f.x_centre(i) > 0.25 && f.x_centre(i) < 0.5 ? 1.0 : 0.0;
    }
  f.fill_ghosts();
  f.set_velocity_from_stream_function([](double, double y) { return y; });  // u = 1, v = 0
  const double volume = f.material_volume(0);
  const int steps = 40;  // Courant 0.4, to t = 0.25
  for (int s = 0; s < steps; ++s) f.step(0.25 / steps);
  double centroid = 0.0;
  for (int i = 0; i < n; ++i) centroid += f.x_centre(i) * f.material(0)(i, 0) * f.dx()[i] * f.dy()[0];
  centroid /= f.material_volume(0) / 4.0;
  std::printf("[materials] contact carried 0.25 by u = 1 on 64 cells: centroid %.6f (0.625), volume %.2e of itself off\n",
              centroid, std::abs(f.material_volume(0) / volume - 1.0));
  EXPECT_NEAR(centroid, 0.625, 0.25 / n);
  EXPECT_LT(std::abs(f.material_volume(0) / volume - 1.0), 1e-13);  // nothing clamped away
}

// Soils of three densities: the mass each face carries (material_sweep's face_density times the
// soil's volume through it) is what the cells' masses, sum_k rho_k q_k, gain and lose, cell by cell,
// over each step (the dilatation terms of the two sweeps cancel in a divergence-free flow).
TEST(MaterialTransport, FacesCarryTheMassOfTheSoilsTheyMove) {
  const int n = 64;
  const double density[3] = {1000.0, 2000.0, 4000.0};  // the base, material 1, material 2
  SerialVofField f(n, n, 1.0, 1.0);
  f.set_boundary(VofBoundary::Empty);
  f.track_materials(2);
  f.set_material_densities({density[0], density[1], density[2]});
  lay_out_disc(f, n, 0.5);
  set_vortex(f);
  const double dt = 0.4 / f.max_courant(1.0), h = 1.0 / n;
  auto mass = [&](int i, int j) {  // per unit volume
    const double c = f.c()(i, j), q1 = c * f.material(0)(i, j), q2 = c * f.material(1)(i, j);
    return density[0] * (c - q1 - q2) + density[1] * q1 + density[2] * q2;
  };
  double worst = 0.0, moved = 0.0, total0 = 0.0, total = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) total0 += mass(i, j) * h * h;
  for (int s = 0; s < 40; ++s) {
    std::vector<double> before;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) before.push_back(mass(i, j));
    for (int a = 0; a < 2; ++a)
      for (int j = -2; j < n + 2; ++j)
        for (int i = -2; i < n + 2; ++i) f.soil_mass_through(a)(i, j) = 0.0;
    f.step(dt);
    const auto& mx = f.soil_mass_through(0);
    const auto& my = f.soil_mass_through(1);
    std::size_t k = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double gained = (mass(i, j) - before[k++]) * h;  // per unit face length
        const double carried_in = mx(i - 1, j) - mx(i, j) + my(i, j - 1) - my(i, j);
        worst = std::max(worst, std::abs(gained - carried_in));
        moved = std::max(moved, std::abs(carried_in));
      }
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) total += mass(i, j) * h * h;
  std::printf("[materials] three densities, 40 steps of the vortex on 64 cells: largest mass a cell gained unlike its "
              "faces' %.2e kg/m^2 of up to %.2e moved; total mass %.2e of itself off\n",
              worst, moved, std::abs(total / total0 - 1.0));
  EXPECT_LT(worst, 1e-12 * moved);
  EXPECT_LT(std::abs(total / total0 - 1.0), 1e-13);
}

// A full cell among full cells of the same material keeps its share, whatever the flow.
TEST(MaterialTransport, UniformMaterialStaysUniform) {
  const int n = 16;
  SerialVofField f(n, n, 1.0, 1.0);
  f.set_boundary(VofBoundary::ZeroGradient);
  f.track_materials(1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      f.c()(i, j) = 1.0;
      f.material(0)(i, j) = 0.3;
    }
  f.fill_ghosts();
  f.set_velocity_from_stream_function([](double x, double y) { return 0.05 * std::sin(kPi * x) * std::sin(kPi * y); });
  for (int s = 0; s < 20; ++s) f.step(0.1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) EXPECT_NEAR(f.material(0)(i, j), 0.3, 1e-13) << i << ", " << j;  // 40 sweeps' round-off
}

}  // namespace
}  // namespace granflow::interface

// Validation: the field-scale collapses of [VoF] Secs. 4.1.2 and 4.2 (cases/bui2008_sph_*.toml), a
// 4 x 2 m block in a 12 x 4 m domain, at half the paper's resolution (150 x 50 cells of 8 cm, about
// 15 s each) to the paper's last time, t = 2.5 s. No SPH data is shipped, so these hold what the
// model must do and what the paper's Figs. 4-7 show: the soil is conserved and the energy budget
// closes; the piles of 45 and 65 degrees come to rest, no steeper than their yield surface allows;
// the 25 degree pile is still spreading at 2.5 s (its surface passes 8 m, [VoF] Sec. 4.1.2); the
// top of the block at the wall stays put (the failure line meets the surface away from the wall);
// the run-out falls as the friction angle or the cohesion rises.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/simulation.hpp"
#include "../verification/test_support.hpp"
#include "../verification/collapse_measures.hpp"

namespace granflow {
namespace {

constexpr double pi = 3.14159265358979323846;

struct SphRun {
  double dx = 0, dy = 0;
  double toe_cell = 0, toe_cell_at_1_4 = 0, toe_contour = 0, wall_height = 0;
  double slope_deg = NAN;  // until measured: a profile that never crosses the marks fails the checks on it
  double volume_error = 0, outflow = 0, energy_ratio = 0, soil_speed = 0;
};

SphRun run_sph(const std::string& case_name, std::vector<std::string> overrides = {}) {
  constexpr int nx = 150, ny = 50;
  SphRun r;
  r.dx = 12.0 / nx;
  r.dy = 4.0 / ny;
  overrides.push_back("output.fields=false");
  auto [run, soil_speed, history, out] = test::run_shipped_case(case_name, nx, ny, overrides);
  r.soil_speed = soil_speed;
  if (!test::is_root()) return r;
  const auto& t = history["time"];
  const size_t n = t.size();
  if (n < 10) return r;
  const size_t k14 = test::first_row_at(t, 1.4);
  r.toe_cell = history["toe_one_cell"][n - 1];
  r.toe_cell_at_1_4 = history["toe_one_cell"][k14];
  r.toe_contour = history["toe_contour"][n - 1];
  r.wall_height = history["wall_height"][n - 1];
  const test::CollapseBudget budget = test::collapse_budget(history);
  r.outflow = budget.outflow;
  r.volume_error = budget.volume_error;
  r.energy_ratio = budget.accounted / budget.released;
  // Mean slope between the points 3/4 and 1/4 as high as the wall, where the column heights first
  // cross them, linear between column centres (as scripts/compare_bui2008_sph.py).
  auto heights = test::read_csv(test::last_output(out, "column_height"));
  const auto& xs = heights["x"];
  const auto& hs = heights["height"];
  auto crossing = [&](double f) {
    const size_t k = size_t(std::find_if(hs.begin(), hs.end(), [&](double h) { return h < f * hs[0]; }) - hs.begin());
    if (k == 0 || k >= xs.size()) return double(NAN);
    return xs[k - 1] + (hs[k - 1] - f * hs[0]) / (hs[k - 1] - hs[k]) * (xs[k] - xs[k - 1]);
  };
  const double hi = crossing(0.75), lo = crossing(0.25);
  if (lo > hi) r.slope_deg = std::atan(0.5 * hs[0] / (lo - hi)) * 180 / pi;  // false for NaN
  std::printf(
      "%s %d x %d to t = %.2f s: %ld steps, %.1f s wall\n"
      "  run-out one cell %.3f m (%.3f m at t = 1.4 s), contour %.3f m; wall height %.3f m; slope %.1f deg\n"
      "  soil volume error %.2e, outflow %.2e; (kinetic + dissipated) / released %.4f; soil speed %.2e m/s\n",
      case_name.c_str(), nx, ny, run.time, run.steps, run.wall_seconds, r.toe_cell, r.toe_cell_at_1_4, r.toe_contour,
      r.wall_height, r.slope_deg, r.volume_error, r.outflow, r.energy_ratio, r.soil_speed);
  return r;
}

// What every case must do: keep its soil, close its energy budget (measured at 150 x 50: +4.9 % for
// 25 degrees, where the arctan density makes partly filled cells heavy, docs/method.md; -4.4, -4.9
// and -1.7 % for the others; within 6 %), and keep the top of the block at the wall.
void expect_conserved_and_wall_kept(const SphRun& r) {
  EXPECT_LT(r.volume_error, 1e-10);
  EXPECT_EQ(r.outflow, 0.0);
  EXPECT_LT(std::abs(r.energy_ratio - 1.0), 0.06);
  EXPECT_GT(r.wall_height, 2.0 - r.dy);
}

// Plane-strain Drucker-Prager ([VoF] Eqs. 7-8) holds sqrt(J_2) = 3 alpha p on a slope at rest, so a
// cohesionless surface cannot stand steeper than asin(3 alpha_phi).
double steepest_slope_deg(double phi_deg) {
  const double tan_phi = std::tan(phi_deg * pi / 180);
  return std::asin(3 * tan_phi / std::sqrt(9 + 12 * tan_phi * tan_phi)) * 180 / pi;
}

// A cohesionless pile at rest: its soil slower than speed_limit, its toe at most one cell further
// than at t = 1.4 s, and its surface no steeper than its yield surface holds. At 1.4 s the piles are
// still slowing down (the 45 degree pile's kinetic energy is a fifth of its value at 1 s and reaches
// its floor by 2 s), so the toe may still step into the next cell.
void expect_pile_at_rest(const SphRun& r, double phi_deg, double speed_limit) {
  EXPECT_LE(std::abs(r.toe_cell - r.toe_cell_at_1_4), r.dx * (1 + 1e-9));
  EXPECT_LT(r.soil_speed, speed_limit);
  EXPECT_LT(r.slope_deg, steepest_slope_deg(phi_deg));
}

// Fig. 4 ([VoF] Sec. 4.1.2): at 2.5 s the 25 degree pile is still spreading, its surface past 8 m.
// Measured: one-cell run-out 7.76 m at 1.4 s and 8.32 m at 2.5 s (8.84 m at 300 x 100, where the
// soil moves at 1.0 m/s).
TEST(Bui2008Sph, Phi25StillSpreadingAtTheLastTime) {
  const SphRun r = run_sph("bui2008_sph_phi25");
  if (!test::is_root()) return;
  expect_conserved_and_wall_kept(r);
  EXPECT_GT(r.toe_cell, r.toe_cell_at_1_4 + 2 * r.dx);
  EXPECT_GT(r.toe_cell, 7.5);
  EXPECT_GT(r.soil_speed, 0.1);
  EXPECT_LT(r.slope_deg, steepest_slope_deg(25.0));
}

// 45 degrees: at rest by 2 s. Measured: one-cell run-out 6.16 m at 1.4 s and 2.5 s (6.40 m at
// 300 x 100, soil speed 1.5e-4 m/s there), slope 25.7 deg (limit 40.9); before the shipped cases' face
// viscosity and coupled solve it was still moving at 0.7-1.1 m/s at 2.5 s, 6.96 m out at 300 x 100.
TEST(Bui2008Sph, Phi45ComesToRest) {
  const SphRun r = run_sph("bui2008_sph_phi45");
  if (!test::is_root()) return;
  expect_conserved_and_wall_kept(r);
  expect_pile_at_rest(r, 45.0, 1e-3);
  EXPECT_GT(r.toe_cell, 6.0);  // past the 65 degree pile's bound below, short of the 25 degree pile's
  EXPECT_LT(r.toe_cell, 7.0);
}

// 65 degrees: at rest by 1.4 s; m = 1e2 caps the viscosity at 2.9e6 Pa s, so the pile creeps at mm/s.
// Measured: one-cell run-out 5.68 m at 1.4 s and 2.5 s (5.76 m at 300 x 100, soil speed 9.2e-3 m/s
// there), slope 29.9 deg (limit 53.1).
TEST(Bui2008Sph, Phi65ComesToRest) {
  const SphRun r = run_sph("bui2008_sph_phi65");
  if (!test::is_root()) return;
  expect_conserved_and_wall_kept(r);
  expect_pile_at_rest(r, 65.0, 2e-2);
  EXPECT_GT(r.toe_cell, 5.0);  // past the cohesive block's bound below
  EXPECT_LT(r.toe_cell, 6.0);
}

// Fig. 7 ([VoF] Sec. 4.2), C = 5 kPa: the block barely slumps, a rigid part stands at the wall and a
// wedge slides off its foot. The case caps the step at 2e-3 s for the paper's times; here 5e-3 s
// (0.4 of the suite's time), which puts the toe one cell behind at 0.8 s and in the same cell from
// 1.1 s on. Measured: one-cell run-out 4.48 m at 1.4 s and 4.56 m at 2.5 s (4.64 m at 300 x 100 with
// the case's step, soil speed 1.5e-2 m/s there: m = 1e2, the rigid part creeps).
TEST(Bui2008Sph, CohesiveBlockBarelySlumps) {
  const SphRun r = run_sph("bui2008_sph_phi25_c5", {"time.max_dt=5e-3"});
  if (!test::is_root()) return;
  expect_conserved_and_wall_kept(r);
  EXPECT_LT(r.toe_cell, 5.0);
  EXPECT_LT(std::abs(r.toe_cell - r.toe_cell_at_1_4), 2 * r.dx);
  EXPECT_LT(r.soil_speed, 5e-2);
}

}  // namespace
}  // namespace granflow

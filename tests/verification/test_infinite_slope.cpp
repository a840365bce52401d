// The factor of safety of an infinite slope (cases/infinite_slope.toml: a periodic layer H = 5 m deep
// on a rough bed at 25 deg, phi = 30 deg, C = 5 kPa) by strength reduction, against the model's own
// closed form.
//
// A layer uniform along the slope shears without normal strain rate, so the model's normal stresses are
// equal, sigma_xx = sigma_yy = -p, and the cone of [VoF] Eqs. 7-9 yields where the shear stress reaches
// sqrt(J_2) = 3 alpha_phi p + k_c. At depth z the shear stress is (rho_s - rho_a) g sin(theta) z (the
// ambient air's weight along the slope is carried by the mean pressure gradient of the periodic sides)
// and the pressure rho_s g cos(theta) z plus the air's column above. The cohesion gains least at depth,
// so the layer fails at the bed when the reduced strength, tan(phi) / F and C / F, meets that stress
// there. The textbook's infinite slope, tau = c + sigma_n tan(phi) on the plane parallel to the surface,
// gives 1.371 for this case; the model gives 1.185 (docs/validation.md, "An infinite slope").
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "io/case_file.hpp"
#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "solver/strength_reduction.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

// The case's layer, read from its file: depth, bed angle, densities, air above.
struct Layer {
  double depth, air_depth, slope_rad, gravity, soil_density, air_density, friction_rad, cohesion;
};

Layer layer_of(const CaseConfig& c) {
  const auto& g = c.flow.gravity;
  const auto box = interface::bounding_box(c.soil->initial_soil.at(0));
  return {box[1][1] - box[0][1],
          c.mesh.upper[1] - box[1][1],
          std::atan2(g[0], -g[1]),
          std::hypot(g[0], g[1]),
          c.soil->soil_density,
          c.soil->air_density,
          c.soil->rheology->friction_angle_deg * deg,
          c.soil->rheology->cohesion};
}

// The factor at which the bed's shear stress meets the reduced cone, [VoF] Eqs. 8-9 with tan(phi) / F
// and C / F, by bisection (the strength falls monotonically with F).
double model_factor(const Layer& l) {
  const double shear = (l.soil_density - l.air_density) * l.gravity * std::sin(l.slope_rad) * l.depth;
  const double pressure =
      (l.soil_density * l.depth + l.air_density * l.air_depth) * l.gravity * std::cos(l.slope_rad);
  auto strength = [&](double factor) {
    const double t = std::tan(l.friction_rad) / factor, root = std::sqrt(9.0 + 12.0 * t * t);
    return 3.0 * t / root * pressure + 3.0 * (l.cohesion / factor) / root;  // 3 alpha_phi p + k_c
  };
  double stands = 0.1, fails = 10.0;
  for (int k = 0; k < 200; ++k) {
    const double middle = 0.5 * (stands + fails);
    (strength(middle) > shear ? stands : fails) = middle;
  }
  return 0.5 * (stands + fails);
}

double textbook_factor(const Layer& l) {
  const double weight = l.soil_density * l.gravity * l.depth;
  return l.cohesion / (weight * std::sin(l.slope_rad) * std::cos(l.slope_rad)) +
         std::tan(l.friction_rad) / std::tan(l.slope_rad);
}

// Half a percent below the model's factor the layer stands through the case's 10 s, half a percent
// above it moves past a tenth of a cell. Measured (bisection to 0.002, the case's 50 outer iterations
// per step): stands at 1.1871 and fails at 1.1883 against 1.1851; without cohesion 1.0451 and 1.0461
// against 1.0444. With 10 outer iterations per step the viscosity lags behind the flow and the
// cohesive layer still stood at 1.1938, so the check above fails: the lag, not the model, would decide.
void expect_bracket(const std::vector<std::string>& overrides, double expected_model, double expected_textbook) {
  std::vector<std::string> keys{"output.progress_seconds=0"};
  keys.insert(keys.end(), overrides.begin(), overrides.end());
  const CaseConfig config = load_case(test::repo_path("cases/infinite_slope.toml"), keys);
  const Layer l = layer_of(config);
  const double model = model_factor(l), textbook = textbook_factor(l);
  EXPECT_NEAR(model, expected_model, 1e-3);  // the closed forms, checked against the numbers quoted above
  EXPECT_NEAR(textbook, expected_textbook, 1e-3);
  const StrengthTrial below = strength_trial(PETSC_COMM_WORLD, config, "", 0.995 * model);
  const StrengthTrial above = strength_trial(PETSC_COMM_WORLD, config, "", 1.005 * model);
  if (test::is_root())
    std::printf("infinite slope, C = %g Pa: model F = %.4f (textbook %.4f); at %.4f moved %.3g m in %.3g s, at %.4f "
                "%.3g m in %.3g s\n",
                l.cohesion, model, textbook, below.factor, below.largest_displacement, below.time, above.factor,
                above.largest_displacement, above.time);
  EXPECT_FALSE(below.fails);
  EXPECT_TRUE(above.fails);
  EXPECT_FALSE(above.diverged);
  // Past the limit the layer yields throughout and its steps stop at the iteration count (all of them,
  // measured); the trial counts them.
  EXPECT_GT(above.unconverged_steps, above.steps / 2);
}

TEST(InfiniteSlope, CohesiveLayerFailsAtTheBedWhereTheModelsConeSaysSo) {
  expect_bracket({}, 1.1851, 1.3712);
}

// Without cohesion every depth reaches its limit together: tan(theta) (1 - rho_a / rho_s) = 3 alpha_phi of
// the reduced friction.
TEST(InfiniteSlope, CohesionlessLayerFailsWhereTheShearStressOverPressureIsThreeAlpha) {
  expect_bracket({"soil.rheology.cohesion=0"}, 1.0444, 1.2382);
}

// The relative shear stress of the layer at rest (the case as it stands, F = 1): the load over the
// strength at each depth, tau(z) / (3 alpha_phi p(z) + k_c), carried by the creep the regularised
// viscosity needs to hold the load (docs/output.md, `relative_shear_stress`). It grows with depth, as
// the cohesion's share of the strength falls: 0.54 at 0.6 m, 0.82 at mid-depth, 0.88 at the bed.
TEST(InfiniteSlope, RelativeShearStressOfTheLayerAtRestIsLoadOverStrength) {
  const CaseConfig config = load_case(test::repo_path("cases/infinite_slope.toml"),
                                      {"output.progress_seconds=0", "time.end=1"});
  const Layer l = layer_of(config);
  Simulation sim(PETSC_COMM_WORLD, config, "");
  sim.run();
  sim.soil()->compute_diagnostics(sim.flow());
  const auto relative = gather_to_root(sim.grid(), sim.soil()->relative_shear_stress());
  if (!test::is_root()) return;
  const Grid& grid = sim.grid();
  const double t = std::tan(l.friction_rad), root = std::sqrt(9.0 + 12.0 * t * t);
  double largest_error = 0.0;
  int checked = 0;
  for (int j = 1; j < grid.ny(); ++j) {
    const double depth = l.depth - grid.yc(j);
    if (depth < 1.5 * grid.dy(j)) break;  // the top cell and the one below it: the surface's
    const double shear = (l.soil_density - l.air_density) * l.gravity * std::sin(l.slope_rad) * depth;
    const double pressure = (l.soil_density * depth + l.air_density * l.air_depth) * l.gravity * std::cos(l.slope_rad);
    const double expected = shear / (3.0 * t / root * pressure + 3.0 * l.cohesion / root);
    for (int i = 0; i < grid.nx(); ++i) {
      const double got = relative[size_t(j) * grid.nx() + i];
      largest_error = std::max(largest_error, std::abs(got / expected - 1.0));
      ++checked;
    }
    if (j % 4 == 1)
      std::printf("depth %.3f m: relative shear stress %.4f, load over strength %.4f\n", depth,
                  relative[size_t(j) * grid.nx()], expected);
  }
  std::printf("relative shear stress over %d cells: largest relative error %.3g\n", checked, largest_error);
  EXPECT_GE(checked, 4 * 17);
  EXPECT_LT(largest_error, 0.02);
}

}  // namespace
}  // namespace granflow

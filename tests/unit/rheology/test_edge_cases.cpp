// Inputs with defined results: rest, non-positive or NaN pressure, +-30 deg and isochoric shear
// exactly, non-finite strain rates. The viscosity is never NaN, infinite or negative.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "models/rheology/granular_rheology.hpp"
#include "rheology_test_utils.hpp"

namespace granflow::rheology {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<RheologyParameters> every_configuration() {
  std::vector<RheologyParameters> all;
  for (Model model : {Model::drucker_prager_bingham, Model::drucker_prager, Model::mohr_coulomb,
                      Model::matsuoka_nakai}) {
    for (FrictionSource friction : {FrictionSource::constant, FrictionSource::mu_of_I}) {
      for (Regularisation reg : {Regularisation::exponential, Regularisation::clip}) {
        if (model == Model::drucker_prager_bingham && friction == FrictionSource::mu_of_I) continue;
        RheologyParameters p;
        p.model = model;
        p.friction = friction;
        p.regularisation = reg;
        all.push_back(p);
      }
    }
  }
  return all;
}

std::string describe(const RheologyParameters& p) {
  return std::string(to_string(p.model)) + "/" + std::string(to_string(p.friction)) + "/" +
         std::string(to_string(p.regularisation));
}

void expect_well_defined(const RheologyResult& r) {
  EXPECT_TRUE(std::isfinite(r.dynamic_viscosity)) << r.dynamic_viscosity;
  EXPECT_GE(r.dynamic_viscosity, 0.0);
  EXPECT_TRUE(std::isfinite(r.kinematic_viscosity));
  EXPECT_GE(r.kinematic_viscosity, 0.0);
  EXPECT_FALSE(std::isnan(r.strain_rate_norm));
  EXPECT_GE(r.lode_angle, -std::numbers::pi / 6.0);
  EXPECT_LE(r.lode_angle, std::numbers::pi / 6.0);
  EXPECT_TRUE(std::isfinite(r.yield_stress));
  EXPECT_GE(r.yield_stress, 0.0);
  EXPECT_TRUE(std::isfinite(r.friction));
  EXPECT_GE(r.yield_pressure, 0.0);
}

TEST(RheologyEdgeCases, NeverNaNInfiniteOrNegative) {
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  const std::vector<StrainRate> rates = {
      StrainRate{},
      StrainRate{-a, b, b, 0, 0, 0},
      StrainRate{a, -b, -b, 0, 0, 0},
      StrainRate{-1, 0, 1, 0, 0, 0},
      planar_strain_rate(0.0, 0.0, 1.0),
      axisymmetric_strain_rate(1.0, -2.0, 0.0, 1.0),
      isotropic_tensor(3.0),
      1e-300 * StrainRate{-1, 0.5, 0.5, 0.1, 0.2, 0.3},
      1e-160 * StrainRate{-1, 0.5, 0.5, 0.1, 0.2, 0.3},
      1e150 * StrainRate{-1, 0.5, 0.5, 0.1, 0.2, 0.3},
      1e300 * StrainRate{-1, 0.5, 0.5, 0.1, 0.2, 0.3},
      StrainRate{kNaN, 0, 0, 0, 0, 0},
      StrainRate{0, 0, 0, kNaN, 0, 0},
      StrainRate{kInf, 0, 0, 0, 0, 0},
      StrainRate{0, 0, 0, kInf, 0, 0},
      StrainRate{-kInf, kInf, 0, 0, 0, 0},
      StrainRate{std::numeric_limits<double>::denorm_min(), 0, 0, 0, 0, 0},
  };
  const std::vector<double> pressures = {0.0,  -1.0, -kInf, kNaN, kInf, 1e-300,
                                         1e3,  1e300, std::numeric_limits<double>::max()};
  std::vector<RheologyParameters> configurations = every_configuration();
  for (RheologyParameters p : every_configuration()) {  // m at the largest a case file takes
    p.regularisation_time = 1e30;
    configurations.push_back(p);
  }
  for (const RheologyParameters& p : configurations) {
    SCOPED_TRACE(describe(p) + " m = " + std::to_string(p.regularisation_time));
    const GranularRheology rheology(p);
    for (std::size_t i = 0; i < rates.size(); ++i) {
      for (double pressure : pressures) {
        SCOPED_TRACE("rate #" + std::to_string(i) + " p = " + std::to_string(pressure));
        const RheologyResult r = rheology.evaluate(rates[i], pressure);
        expect_well_defined(r);
        EXPECT_EQ(rheology.dynamic_viscosity(rates[i], pressure), r.dynamic_viscosity);
      }
    }
  }
}

TEST(RheologyEdgeCases, RandomSweepStaysFiniteAndNonNegative) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> pressure(-1e3, 1e6);
  for (const RheologyParameters& p : every_configuration()) {
    const GranularRheology rheology(p);
    for (int i = 0; i < 5000; ++i) {
      const double eta =
          rheology.dynamic_viscosity(testing::random_traceless_strain_rate(rng), pressure(rng));
      ASSERT_TRUE(std::isfinite(eta)) << describe(p);
      ASSERT_GE(eta, 0.0) << describe(p);
    }
  }
}

TEST(RheologyEdgeCases, RestGivesTheRegularisedMaximum) {
  for (RheologyParameters p : every_configuration()) {
    SCOPED_TRACE(describe(p));
    const GranularRheology rheology(p);
    const double pressure = 1e3;
    const RheologyResult rest = rheology.evaluate(StrainRate{}, pressure);
    EXPECT_EQ(rest.strain_rate_norm, 0.0);
    EXPECT_EQ(rest.lode_angle, 0.0);
    const double expected = p.regularisation == Regularisation::exponential
                                ? p.min_dynamic_viscosity + p.regularisation_time * rest.yield_stress
                                : p.density * p.max_kinematic_viscosity;
    EXPECT_DOUBLE_EQ(rest.dynamic_viscosity, expected);
    // Nothing moving is stiffer than the rest state.
    EXPECT_GE(rest.dynamic_viscosity,
              rheology.dynamic_viscosity(planar_strain_rate(0, 0, 1e-8), pressure));
  }
}

TEST(RheologyEdgeCases, NonPositiveOrNaNPressureMeansNoFrictionalStrength) {
  for (RheologyParameters p : every_configuration()) {
    SCOPED_TRACE(describe(p));
    const GranularRheology rheology(p);
    const double floor = p.regularisation == Regularisation::exponential
                             ? p.min_dynamic_viscosity
                             : p.density * p.min_kinematic_viscosity;
    for (double pressure : {0.0, -5e3, -kInf, kNaN}) {
      for (const StrainRate& d : {StrainRate{}, planar_strain_rate(0, 0, 2.0)}) {
        const RheologyResult r = rheology.evaluate(d, pressure);
        EXPECT_EQ(r.yield_pressure, 0.0);
        EXPECT_EQ(r.yield_stress, 0.0);
        EXPECT_DOUBLE_EQ(r.dynamic_viscosity, floor);
      }
    }
  }
}

TEST(RheologyEdgeCases, CohesionIsTheOnlyStrengthAtZeroPressure) {
  RheologyParameters p;
  p.model = Model::drucker_prager_bingham;
  p.friction_angle_deg = 25.0;
  p.cohesion = 5e3;
  const GranularRheology rheology(p);
  const RheologyResult tension = rheology.evaluate(StrainRate{}, -1e4);  // clipped: no tension
  const RheologyResult zero = rheology.evaluate(StrainRate{}, 0.0);
  EXPECT_DOUBLE_EQ(tension.yield_stress, rheology.drucker_prager_bingham().cohesion_term);
  EXPECT_DOUBLE_EQ(tension.dynamic_viscosity, zero.dynamic_viscosity);
}

TEST(RheologyEdgeCases, NaNStrainRateIsTreatedAsRest) {
  for (RheologyParameters p : every_configuration()) {
    const GranularRheology rheology(p);
    EXPECT_EQ(rheology.dynamic_viscosity(StrainRate{kNaN, kNaN, 0, 0, 0, 0}, 1e3),
              rheology.dynamic_viscosity(StrainRate{}, 1e3))
        << describe(p);
  }
}

TEST(RheologyEdgeCases, LodeAngleExtremesAndIsochoricShearExactly) {
  RheologyParameters p;
  p.friction_angle_deg = 36.5;
  p.regularisation = Regularisation::clip;
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  const double friction = std::sin(36.5 * std::numbers::pi / 180.0);
  for (Model model : {Model::drucker_prager, Model::mohr_coulomb, Model::matsuoka_nakai}) {
    p.model = model;
    const GranularRheology rheology(p);
    const RheologyResult txc = rheology.evaluate(StrainRate{-a, b, b, 0, 0, 0}, 1.0);
    const RheologyResult txe = rheology.evaluate(StrainRate{a, -b, -b, 0, 0, 0}, 1.0);
    const RheologyResult shr = rheology.evaluate(StrainRate{-1, 0, 1, 0, 0, 0}, 1.0);
    EXPECT_DOUBLE_EQ(txc.lode_angle, -std::numbers::pi / 6.0);
    EXPECT_DOUBLE_EQ(txe.lode_angle, std::numbers::pi / 6.0);
    EXPECT_EQ(shr.lode_angle, 0.0);  // Matsuoka-Nakai's third branch, I_3(D) = 0 exactly
    EXPECT_NEAR(shr.yield_stress, friction, 2e-15);
    EXPECT_TRUE(std::isfinite(txc.yield_stress) && std::isfinite(txe.yield_stress));
  }
}

}  // namespace
}  // namespace granflow::rheology

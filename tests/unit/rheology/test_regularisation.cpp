// The two regularisations: exponential (Papanastasiou, [VoF] Eq. 12) and clipping ([YS] Sec. 2.4).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "models/rheology/granular_rheology.hpp"
#include "rheology_test_utils.hpp"

namespace granflow::rheology {
namespace {

RheologyParameters bui2008_experiment() {
  RheologyParameters p;  // [VoF] Sec. 4.1: aluminium bars, phi = 19.8, C = 0, m = 1e5
  p.model = Model::drucker_prager_bingham;
  p.regularisation = Regularisation::exponential;
  p.friction_angle_deg = 19.8;
  p.cohesion = 0.0;
  p.regularisation_time = 1e5;
  p.min_dynamic_viscosity = 1e-3;
  p.density = 2650.0;
  return p;
}

// That material's yield stress 3 alpha_phi p + k_c ([VoF] Eqs. 8-9, C = 0), from its friction angle.
double bui2008_yield_stress(double pressure) {
  const double tan_phi = std::tan(19.8 * std::numbers::pi / 180.0);
  return 3.0 * tan_phi / std::sqrt(9.0 + 12.0 * tan_phi * tan_phi) * pressure;
}

TEST(RheologyRegularisation, BinghamMaximumViscosityOfTheBuiBlock) {
  // mu_max = m (3 alpha_phi p + k_c) at vanishing strain rate ([VoF] Sec. 2), with p = rho g h
  // at the bottom of the 0.1 m block: about 8.6e7 Pa s.
  const GranularRheology rheology(bui2008_experiment());
  const double pressure = 2650.0 * 9.81 * 0.1;
  const double tan_phi = std::tan(19.8 * std::numbers::pi / 180.0);
  const double alpha_phi = tan_phi / std::sqrt(9.0 + 12.0 * tan_phi * tan_phi);  // Eq. 8
  const double k_c = 0.0;                                                        // Eq. 9, C = 0
  const double mu_max = 1e5 * (3.0 * alpha_phi * pressure + k_c);

  const double eta_rest = rheology.dynamic_viscosity(StrainRate{}, pressure);
  EXPECT_NEAR(eta_rest - 1e-3, mu_max, 1e-13 * mu_max);  // the formula, to round-off
  EXPECT_NEAR(eta_rest, 8.6e7, 0.05e7);                  // the printed two digits
  char printed[16];
  std::snprintf(printed, sizeof printed, "%.1e", eta_rest);
  EXPECT_STREQ(printed, "8.6e+07");

  // Vanishing (not zero) strain rate approaches the same limit.
  const double eta_small = rheology.dynamic_viscosity(planar_strain_rate(0.0, 0.0, 1e-12), pressure);
  EXPECT_NEAR(eta_small, eta_rest, 1e-6 * eta_rest);
  EXPECT_LT(eta_small, eta_rest);
}

TEST(RheologyRegularisation, BinghamRestViscosityIncludesCohesion) {
  RheologyParameters p = bui2008_experiment();
  p.friction_angle_deg = 25.0;
  p.cohesion = 5e3;
  p.regularisation_time = 1e2;
  const GranularRheology rheology(p);
  const double tan_phi = std::tan(25.0 * std::numbers::pi / 180.0);
  const double root = std::sqrt(9.0 + 12.0 * tan_phi * tan_phi);
  for (double pressure : {0.0, 1e3, 3e4}) {
    const double expected = 1e-3 + 1e2 * (3.0 * tan_phi / root * pressure + 3.0 * 5e3 / root);
    EXPECT_NEAR(rheology.dynamic_viscosity(StrainRate{}, pressure), expected, 1e-13 * expected);
  }
}

TEST(RheologyRegularisation, ExponentialFormIsEquation12WithTheVofNorm) {
  // [VoF] Eq. 12 written with sqrt(2 e:e) directly, compared with the library (which uses 2||D||).
  const RheologyParameters p = bui2008_experiment();
  const GranularRheology rheology(p);
  const auto& dp = rheology.drucker_prager_bingham();
  std::mt19937_64 rng(12);
  for (int i = 0; i < 500; ++i) {
    const StrainRate e = testing::random_traceless_strain_rate(rng);
    const double pressure = 500.0 + 100.0 * i;
    const double magnitude = vof_strain_rate_magnitude(e);
    const double tau = 3.0 * dp.alpha_phi * pressure + dp.cohesion_term;
    const double eq12 = p.min_dynamic_viscosity +
                        tau / magnitude * (1.0 - std::exp(-p.regularisation_time * magnitude));
    EXPECT_NEAR(rheology.dynamic_viscosity(e, pressure), eq12, 1e-12 * eq12);
  }
}

TEST(RheologyRegularisation, ExponentialTendsToPlasticViscosityAtLargeRates) {
  // Beyond 1/m the exponential term vanishes and eta -> mu_min + Eq. 11.
  const GranularRheology rheology(bui2008_experiment());
  const StrainRate d = planar_strain_rate(0.0, 0.0, 0.5);  // ||D|| = 0.5, sqrt(2 e:e) = 1
  const RheologyResult r = rheology.evaluate(d, 1000.0);
  EXPECT_NEAR(r.yield_stress, bui2008_yield_stress(1000.0), 1e-12 * r.yield_stress);
  EXPECT_NEAR(r.dynamic_viscosity, 1e-3 + bui2008_yield_stress(1000.0) / 1.0, 1e-12 * r.dynamic_viscosity);
}

TEST(RheologyRegularisation, ExponentialIsIndependentOfTheModel) {
  // Mohr-Coulomb with the exponential regularisation: rest value mu_min + m tau_y(theta).
  RheologyParameters p;
  p.model = Model::mohr_coulomb;
  p.regularisation = Regularisation::exponential;
  p.friction_angle_deg = 36.5;
  p.regularisation_time = 1e3;
  const GranularRheology rheology(p);
  const double pressure = 1000.0;
  const double eta_rest = rheology.dynamic_viscosity(StrainRate{}, pressure);
  EXPECT_NEAR(eta_rest, 1e-3 + 1e3 * std::sin(36.5 * std::numbers::pi / 180.0) * pressure,
              1e-9 * eta_rest);
  // At large rates the compression state is stronger than the extension state.
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  EXPECT_GT(rheology.dynamic_viscosity(StrainRate{-a, b, b, 0, 0, 0}, pressure),
            rheology.dynamic_viscosity(StrainRate{a, -b, -b, 0, 0, 0}, pressure));
}

TEST(RheologyRegularisation, ClipKeepsKinematicViscosityWithinBounds) {
  RheologyParameters p;  // [YS] Sec. 4: rho_s = 1430, nu in [1e-5, 1]
  p.model = Model::matsuoka_nakai;
  p.regularisation = Regularisation::clip;
  p.friction_angle_deg = 36.5;
  p.density = 1430.0;
  const GranularRheology rheology(p);
  EXPECT_DOUBLE_EQ(rheology.kinematic_viscosity(StrainRate{}, 1000.0), 1.0);
  EXPECT_DOUBLE_EQ(rheology.dynamic_viscosity(StrainRate{}, 1000.0), 1430.0);
  EXPECT_DOUBLE_EQ(rheology.kinematic_viscosity(planar_strain_rate(0, 0, 1e9), 1000.0), 1e-5);
  // In between: exactly the plastic viscosity (Eq. 30 third branch for planar shear).
  const StrainRate d = planar_strain_rate(0.0, 0.0, 50.0);
  const RheologyResult r = rheology.evaluate(d, 1000.0);
  const double plastic = std::sin(36.5 * std::numbers::pi / 180.0) * 1000.0 / (2.0 * 50.0);
  EXPECT_NEAR(r.dynamic_viscosity, plastic, 1e-12 * plastic);
  EXPECT_NEAR(r.kinematic_viscosity, plastic / 1430.0, 1e-12 * plastic);
  std::mt19937_64 rng(8);
  for (int i = 0; i < 1000; ++i) {
    const double nu = rheology.kinematic_viscosity(testing::random_traceless_strain_rate(rng),
                                                   10.0 * i);
    EXPECT_GE(nu, 1e-5);
    EXPECT_LE(nu, 1.0);
  }
}

TEST(RheologyRegularisation, ClipIsIndependentOfTheModel) {
  // Drucker-Prager-Bingham strength with clipping instead of the exponential.
  RheologyParameters p = bui2008_experiment();
  p.regularisation = Regularisation::clip;
  const GranularRheology rheology(p);
  EXPECT_DOUBLE_EQ(rheology.dynamic_viscosity(StrainRate{}, 2599.65), 2650.0 * 1.0);
  const StrainRate d = planar_strain_rate(0.0, 0.0, 5.0);
  const RheologyResult r = rheology.evaluate(d, 2599.65);
  EXPECT_NEAR(r.dynamic_viscosity, bui2008_yield_stress(2599.65) / (2.0 * 5.0), 1e-12 * r.dynamic_viscosity);
}

TEST(RheologyRegularisation, ViscosityDecreasesMonotonicallyWithStrainRate) {
  for (Regularisation reg : {Regularisation::exponential, Regularisation::clip}) {
    RheologyParameters p;
    p.model = Model::drucker_prager;
    p.regularisation = reg;
    const GranularRheology rheology(p);
    double previous = rheology.dynamic_viscosity(StrainRate{}, 1e3);
    for (double rate = 1e-9; rate < 1e6; rate *= 1.5) {
      const double eta = rheology.dynamic_viscosity(planar_strain_rate(0, 0, rate), 1e3);
      EXPECT_LE(eta, previous * (1.0 + 1e-14)) << to_string(reg) << " rate " << rate;
      previous = eta;
    }
  }
}

}  // namespace
}  // namespace granflow::rheology

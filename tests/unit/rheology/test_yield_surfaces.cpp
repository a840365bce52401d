// The viscosities put the stress T = 2 eta D - p I on each model's yield surface f(T) = 0, where
// f is written independently from the stress tensor ([VoF] Eq. 7; [YS] Eqs. 23, 26, 29).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "models/rheology/drucker_prager.hpp"
#include "models/rheology/drucker_prager_bingham.hpp"
#include "models/rheology/granular_rheology.hpp"
#include "models/rheology/invariants.hpp"
#include "models/rheology/matsuoka_nakai.hpp"
#include "models/rheology/mohr_coulomb.hpp"
#include "rheology_test_utils.hpp"

namespace granflow::rheology {
namespace {

constexpr double kYieldTolerance = 1e-10;

// Dimensionless yield function of the model at stress T, using the friction the rheology used. A
// cohesion C moves the [YS] surfaces' apex to p = -C cot(phi): their yield function is then the
// cohesionless one of the stress T - C cot(phi) I; Mohr-Coulomb's is written out with C instead
// (Eq. 26 in stress units), which also holds at phi = 0 (Tresca).
double yield_function_of(const GranularRheology& rheology, const SymmetricTensor& stress,
                         double friction, double pressure) {
  const RheologyParameters& p = rheology.parameters();
  const double phi = p.friction_angle_deg * std::numbers::pi / 180.0;
  const double cohesion_cos_phi = p.cohesion * std::cos(phi);
  const double attraction = p.cohesion > 0.0 ? cohesion_cos_phi / std::sin(phi) : 0.0;
  const SymmetricTensor shifted = stress - isotropic_tensor(attraction);
  switch (p.model) {
    case Model::drucker_prager_bingham:
      return rheology.drucker_prager_bingham().yield_function(stress) / pressure;
    case Model::drucker_prager:
      return drucker_prager_yield_function(shifted, friction) / pressure;
    case Model::mohr_coulomb:
      if (p.cohesion > 0.0) return mohr_coulomb_yield_function(stress, friction, cohesion_cos_phi) / pressure;
      return mohr_coulomb_yield_function(stress, friction);
    case Model::matsuoka_nakai: {
      const double k = p.matsuoka_nakai_fit == MatsuokaNakaiFit::isochoric_shear
                           ? matsuoka_nakai_k_isochoric(friction)
                           : matsuoka_nakai_k_triaxial(friction);
      return matsuoka_nakai_yield_function(shifted, k);
    }
  }
  return 1.0;
}

std::vector<RheologyParameters> all_model_variants() {
  std::vector<RheologyParameters> variants;
  for (Model model : {Model::drucker_prager_bingham, Model::drucker_prager, Model::mohr_coulomb,
                      Model::matsuoka_nakai}) {
    for (FrictionSource friction : {FrictionSource::constant, FrictionSource::mu_of_I}) {
      if (model == Model::drucker_prager_bingham && friction == FrictionSource::mu_of_I) continue;
      RheologyParameters p;
      p.model = model;
      p.friction = friction;
      p.friction_angle_deg = 36.5;
      p.density = 1430.0;
      variants.push_back(p);
      if (friction == FrictionSource::constant) {
        p.cohesion = 5e3;  // [VoF] Fig. 7 case
        p.friction_angle_deg = 25.0;
        variants.push_back(p);
        if (model == Model::mohr_coulomb) {  // Tresca
          p.friction_angle_deg = 0.0;
          variants.push_back(p);
        }
        p.cohesion = 0.0;
        p.friction_angle_deg = 36.5;
      }
      if (model == Model::matsuoka_nakai) {
        p.matsuoka_nakai_fit = MatsuokaNakaiFit::triaxial;
        variants.push_back(p);
        if (friction == FrictionSource::constant) {
          p.cohesion = 5e3;
          variants.push_back(p);
        }
      }
    }
  }
  return variants;
}

std::string describe(const RheologyParameters& p) {
  return std::string(to_string(p.model)) + "/" + std::string(to_string(p.friction)) + "/" +
         std::string(to_string(p.matsuoka_nakai_fit)) + "/C=" + std::to_string(p.cohesion);
}

TEST(RheologyYieldSurface, UnregularisedStressLiesOnEveryModelsSurface) {
  std::mt19937_64 rng(2020);
  std::uniform_real_distribution<double> log_pressure(1.0, 5.0);
  for (const RheologyParameters& parameters : all_model_variants()) {
    SCOPED_TRACE(describe(parameters));
    const GranularRheology rheology(parameters);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const StrainRate d = testing::random_traceless_strain_rate(rng);
      const double pressure = std::pow(10.0, log_pressure(rng));
      const RheologyResult r = rheology.evaluate(d, pressure);
      const double eta = plastic_viscosity(r.yield_stress, r.strain_rate_norm);  // no regularisation
      const SymmetricTensor stress = deviatoric_stress(d, eta) - isotropic_tensor(pressure);
      const double f = yield_function_of(rheology, stress, r.friction, pressure);
      worst = std::max(worst, std::abs(f));
      ASSERT_LT(std::abs(f), kYieldTolerance) << "theta = " << r.lode_angle << " p = " << pressure;
    }
    std::ostringstream worst_text;
    worst_text << std::scientific << worst;
    RecordProperty("worst_" + describe(parameters), worst_text.str());
  }
}

TEST(RheologyYieldSurface, StressOnSurfaceAtTheSpecialLodeAngles) {
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  for (const RheologyParameters& parameters : all_model_variants()) {
    SCOPED_TRACE(describe(parameters));
    const GranularRheology rheology(parameters);
    for (const StrainRate& d : {StrainRate{-a, b, b, 0, 0, 0}, StrainRate{a, -b, -b, 0, 0, 0},
                                StrainRate{-1, 0, 1, 0, 0, 0}, planar_strain_rate(0.2, -0.2, 0.4),
                                axisymmetric_strain_rate(1.0, -2.0, 0.0, 1.0)}) {
      const double pressure = 2000.0;
      const RheologyResult r = rheology.evaluate(d, pressure);
      const double eta = plastic_viscosity(r.yield_stress, r.strain_rate_norm);
      const SymmetricTensor stress = deviatoric_stress(d, eta) - isotropic_tensor(pressure);
      EXPECT_LT(std::abs(yield_function_of(rheology, stress, r.friction, pressure)),
                kYieldTolerance);
    }
  }
}

TEST(RheologyYieldSurface, YieldFunctionsAreNegativeInsideAndPositiveOutsideOrdering) {
  // A check that f(T) is a real test: the surface stress scaled by 0.9 is inside, by 1.1 outside.
  const double friction = std::sin(36.5 * std::numbers::pi / 180.0);
  const double k = matsuoka_nakai_k_isochoric(friction);
  const StrainRate d{-1.0, 0.3, 0.7, 0.2, -0.1, 0.05};
  const double pressure = 1000.0;
  const double theta = lode_angle(d);
  const double rate = norm(deviatoric(d));
  const double mc_tau = mohr_coulomb_yield_stress(friction, theta, pressure);
  const double mn_tau = MatsuokaNakai::from_k(k).yield_stress(
      std::sin(3.0 * theta), pressure);
  for (double scale : {0.9, 1.1}) {
    const auto stress_for = [&](double tau) {
      return deviatoric_stress(d, scale * plastic_viscosity(tau, rate)) -
             isotropic_tensor(pressure);
    };
    const double sign = scale < 1.0 ? -1.0 : 1.0;
    EXPECT_GT(sign * mohr_coulomb_yield_function(stress_for(mc_tau), friction), 1e-3);
    EXPECT_GT(sign * matsuoka_nakai_yield_function(stress_for(mn_tau), k), 1e-3);
    // DP's f is positive inside (Eq. 23), hence the opposite sign.
    EXPECT_GT(-sign * drucker_prager_yield_function(stress_for(friction * pressure), friction),
              1e-3);
  }
}

TEST(RheologyYieldSurface, MohrCoulombAndMatsuokaNakaiEqualDruckerPragerInIsochoricShear) {
  std::mt19937_64 rng(36);
  for (double phi_deg : {10.0, 19.8, 25.0, 36.5, 45.0, 65.0, 80.0}) {
    const double friction = std::sin(phi_deg * std::numbers::pi / 180.0);
    const MatsuokaNakai mn = MatsuokaNakai::from_k(matsuoka_nakai_k_isochoric(friction));
    // theta = 0 exactly: Eq. 28 reduces to Eq. 24, Eq. 30's third branch to sin(phi).
    EXPECT_NEAR(mohr_coulomb_stress_ratio(friction, 0.0), friction, 1e-15);
    EXPECT_NEAR(mn.stress_ratio(0.0), friction, 2e-15);
    // Rotated isochoric shear: det(D) is only zero to round-off, the general branch is taken.
    for (int i = 0; i < 100; ++i) {
      const StrainRate d =
          testing::rotate(StrainRate{-1.0, 0.0, 1.0, 0, 0, 0}, testing::random_rotation(rng));
      const DeformationState s = deformation_state(d);
      EXPECT_NEAR(mohr_coulomb_stress_ratio(friction, lode_angle_from_sin3(s.sin_three_lode)),
                  friction, 1e-14);
      EXPECT_NEAR(mn.stress_ratio(s.sin_three_lode), friction, 1e-14);
    }
  }
}

TEST(RheologyYieldSurface, MatsuokaNakaiStableFormEqualsEquation30WithResolvedBranches) {
  const double friction = std::sin(36.5 * std::numbers::pi / 180.0);
  const double k = matsuoka_nakai_k_isochoric(friction);
  const MatsuokaNakai mn = MatsuokaNakai::from_k(k);
  std::mt19937_64 rng(30);
  int compression = 0, extension = 0;
  for (int i = 0; i < 5000; ++i) {
    const StrainRate d = testing::random_traceless_strain_rate(rng);
    const DeformationState s = deformation_state(d);
    if (std::abs(s.sin_three_lode) < 1e-3) continue;  // Eq. 30 is ill-conditioned near I_3 = 0
    (s.sin_three_lode < 0.0 ? compression : extension) += 1;
    const double pressure = 1000.0;
    const double eta_paper = matsuoka_nakai_viscosity_eq30(d, pressure, k);
    const double eta_stable =
        plastic_viscosity(mn.yield_stress(s.sin_three_lode, pressure), s.strain_rate_norm);
    EXPECT_NEAR(eta_paper, eta_stable, 1e-9 * eta_stable);
  }
  EXPECT_GT(compression, 1000);
  EXPECT_GT(extension, 1000);
}

TEST(RheologyYieldSurface, PrintedArctanOfEquation33MissesTriaxialCompression) {
  // Why Eq. 33 needs the quadrant: with the printed principal-value arctan, branch 1 of Eq. 30
  // (theta < 0) gives 0.275 at TXC instead of Table 1's 0.380, while the resolved form gives 0.380.
  const double friction = std::sin(36.5 * std::numbers::pi / 180.0);
  const double k = matsuoka_nakai_k_isochoric(friction);
  const StrainRate d{-2.0 / std::numbers::sqrt3, 1.0 / std::numbers::sqrt3,
                     1.0 / std::numbers::sqrt3, 0, 0, 0};
  const double i2 = second_invariant(d), i3 = third_invariant(d);
  const double a = i2 * (3.0 - k) / (i3 * k), b = (9.0 - k) / (i3 * k);
  const double gamma_printed =
      std::atan(-3.0 * std::sqrt(-3.0 * (4.0 * a * a * a * b + 27.0 * b * b)) /
                (-2.0 * a * a * a - 27.0 * b)) / 3.0;
  const double eta_printed =
      a * (std::cos(gamma_printed) - std::numbers::sqrt3 * std::sin(gamma_printed) - 1.0) / 6.0;
  EXPECT_NEAR(eta_printed, 0.2747, 5e-4);
  EXPECT_NEAR(matsuoka_nakai_viscosity_eq30(d, 1.0, k), 0.3798, 5e-4);
}

TEST(RheologyYieldSurface, TriaxialFitOfMatsuokaNakaiMatchesMohrCoulombAtThirtyDegrees) {
  for (double phi_deg : {20.0, 36.5, 50.0}) {
    const double friction = std::sin(phi_deg * std::numbers::pi / 180.0);
    const MatsuokaNakai mn = MatsuokaNakai::from_k(matsuoka_nakai_k_triaxial(friction));
    constexpr double sixth_pi = std::numbers::pi / 6.0;
    EXPECT_NEAR(mn.stress_ratio(-1.0), mohr_coulomb_stress_ratio(friction, -sixth_pi), 1e-12);
    EXPECT_NEAR(mn.stress_ratio(1.0), mohr_coulomb_stress_ratio(friction, sixth_pi), 1e-12);
    // Through the MC corners, MN bulges outside MC in between: stronger than DP in shear.
    EXPECT_GT(mn.stress_ratio(0.0), friction * 1.01);
  }
}

TEST(RheologyYieldSurface, DruckerPragerBinghamParametersFromEquations8And9) {
  const double phi = 25.0 * std::numbers::pi / 180.0;
  const auto dp = DruckerPragerBingham::from_friction_angle(phi, 5e3);
  const double t = std::tan(phi);
  EXPECT_DOUBLE_EQ(dp.alpha_phi, t / std::sqrt(9.0 + 12.0 * t * t));
  EXPECT_DOUBLE_EQ(dp.cohesion_term, 15e3 / std::sqrt(9.0 + 12.0 * t * t));
  EXPECT_DOUBLE_EQ(dp.yield_stress(1000.0), 3.0 * dp.alpha_phi * 1000.0 + dp.cohesion_term);
}

// In simple shear at constant volume (the sliding layers of a collapse) the shear stress on the
// sliding plane over the normal stress p is the model's friction coefficient. With the plane-strain
// fit of [VoF] Eq. 8 it is 3 alpha_phi = tan(phi) / sqrt(1 + 4/3 tan^2 phi), below tan(phi) of the
// shear box that measured phi: 0.3324 against 0.3600 at 19.8 deg (docs/validation.md).
TEST(RheologyYieldSurface, DruckerPragerBinghamFrictionInSimpleShearIsThreeAlpha) {
  auto shear_friction = [](double phi_deg) {
    RheologyParameters p;
    p.model = Model::drucker_prager_bingham;
    p.friction_angle_deg = phi_deg;
    const GranularRheology rheology(p);
    const double pressure = 800.0, shear_rate = 50.0;  // du/dy, so D_xy = shear_rate / 2
    const StrainRate d = planar_strain_rate(0.0, 0.0, 0.5 * shear_rate);
    const RheologyResult r = rheology.evaluate(d, pressure);
    const double eta = plastic_viscosity(r.yield_stress, r.strain_rate_norm);
    return deviatoric_stress(d, eta).xy / pressure;
  };
  const double deg = std::numbers::pi / 180.0;
  EXPECT_NEAR(shear_friction(19.8), 0.3324, 1e-4);
  EXPECT_NEAR(shear_friction(19.8) / std::tan(19.8 * deg), 0.923, 1e-3);
  // The cone that gives the shear box's friction in simple shear: 21.6 deg.
  EXPECT_NEAR(shear_friction(21.6), std::tan(19.8 * deg), 1e-4);
}

}  // namespace
}  // namespace granflow::rheology

// mu(I) of Jop, Forterre & Pouliquen (2006) in place of sin(phi) ([YS] Eq. 25, Sec. 6).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "models/rheology/granular_rheology.hpp"
#include "models/rheology/mu_of_i.hpp"

namespace granflow::rheology {
namespace {

TEST(RheologyMuOfI, FrictionLimitsAndMidpoint) {
  const MuOfI law{0.38, 0.64, 0.279};
  EXPECT_DOUBLE_EQ(law.friction(0.0), 0.38);
  EXPECT_DOUBLE_EQ(law.friction(std::numeric_limits<double>::infinity()), 0.64);
  EXPECT_DOUBLE_EQ(law.friction(0.279), 0.5 * (0.38 + 0.64));
  EXPECT_NEAR(law.friction(0.1), 0.38 + 0.26 / (2.79 + 1.0), 1e-15);
}

TEST(RheologyMuOfI, InertialNumberUsesTheShearRateTwiceTheNorm) {
  // Simple shear with rate gamma: ||D|| = gamma / 2, I = gamma d / sqrt(p / rho_s).
  const double gamma = 10.0, d = 0.5e-3, rho = 2450.0, p = 200.0;
  const double rate = norm(planar_strain_rate(0.0, 0.0, 0.5 * gamma));
  EXPECT_NEAR(inertial_number(rate, d, rho, p), gamma * d / std::sqrt(p / rho), 1e-15);
}

TEST(RheologyMuOfI, ViscosityIsEquation25InsideTheClipBounds) {
  RheologyParameters params;
  params.model = Model::drucker_prager;
  params.friction = FrictionSource::mu_of_I;
  params.regularisation = Regularisation::clip;
  params.density = 2450.0;
  params.grain_diameter = 0.5e-3;
  const GranularRheology rheology(params);
  const double gamma = 20.0, p = 500.0;
  const StrainRate d = planar_strain_rate(0.0, 0.0, 0.5 * gamma);
  const double inertial = gamma * 0.5e-3 / std::sqrt(p / 2450.0);
  const double mu = 0.38 + (0.64 - 0.38) / (0.279 / inertial + 1.0);
  const RheologyResult r = rheology.evaluate(d, p);
  EXPECT_NEAR(r.friction, mu, 1e-14);
  EXPECT_NEAR(r.dynamic_viscosity, mu * p / gamma, 1e-12 * r.dynamic_viscosity);  // mu p/(2||D||)
  // Faster shear means more friction than the constant-angle model with sin(phi) = mu_s.
  EXPECT_GT(r.friction, 0.38);
}

TEST(RheologyMuOfI, CombinesWithMohrCoulombAndMatsuokaNakai) {
  // With a Lode angle, mu(I) scales the Mohr-Coulomb / Matsuoka-Nakai surfaces exactly as
  // sin(phi) does: same friction, same yield stress as the constant model with sin(phi) = mu.
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  const StrainRate txc{-a, b, b, 0, 0, 0};
  const double p = 800.0;
  for (Model model : {Model::mohr_coulomb, Model::matsuoka_nakai}) {
    RheologyParameters dynamic;
    dynamic.model = model;
    dynamic.friction = FrictionSource::mu_of_I;
    dynamic.regularisation = Regularisation::clip;
    const RheologyResult r = GranularRheology(dynamic).evaluate(txc, p);
    RheologyParameters constant = dynamic;
    constant.friction = FrictionSource::constant;
    constant.friction_angle_deg = std::asin(r.friction) * 180.0 / std::numbers::pi;
    const RheologyResult c = GranularRheology(constant).evaluate(txc, p);
    EXPECT_NEAR(r.yield_stress, c.yield_stress, 1e-11 * c.yield_stress) << to_string(model);
    EXPECT_GT(r.yield_stress, r.friction * p);  // compression: above Drucker-Prager
  }
}

}  // namespace
}  // namespace granflow::rheology

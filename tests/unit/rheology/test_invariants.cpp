// Norm conventions, invariants and the Lode angle ([YS] Eqs. 5-12, [VoF] Eqs. 10-12).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "models/rheology/invariants.hpp"
#include "rheology_test_utils.hpp"

namespace granflow::rheology {
namespace {

constexpr double kSixthPi = std::numbers::pi / 6.0;

TEST(RheologyInvariants, NormIsHalfTraceOfSquareNotFrobenius) {
  // Simple shear u = (gamma y, 0, 0): D_xy = gamma / 2, ||D|| = gamma / 2 ([YS] Eq. 8), while the
  // Frobenius norm is gamma / sqrt2.
  const double gamma = 3.0;
  const StrainRate d = planar_strain_rate(0.0, 0.0, 0.5 * gamma);
  EXPECT_NEAR(norm(d), 0.5 * gamma, 1e-15);
  EXPECT_NEAR(std::sqrt(double_contraction(d, d)), gamma / std::numbers::sqrt2, 1e-15);
}

TEST(RheologyInvariants, VofMagnitudeIsTwiceYsNorm) {
  // sqrt(2 e:e) of [VoF] Eqs. 10-12 equals 2 ||D|| of [YS] Eq. 8; the factor 2 is where the two
  // papers would otherwise be mixed up.
  std::mt19937_64 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const StrainRate d = testing::random_traceless_strain_rate(rng);
    EXPECT_NEAR(vof_strain_rate_magnitude(d), 2.0 * norm(d), 1e-13 * norm(d));
    EXPECT_GT(std::abs(vof_strain_rate_magnitude(d) - norm(d)), 0.5 * norm(d));
  }
  // Simple shear with rate gamma: sqrt(2 e:e) = gamma.
  EXPECT_NEAR(vof_strain_rate_magnitude(planar_strain_rate(0.0, 0.0, 0.5)), 1.0, 1e-15);
}

TEST(RheologyInvariants, SecondInvariantOfTracelessTensorIsMinusNormSquared) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 200; ++i) {
    const StrainRate d = testing::random_traceless_strain_rate(rng);
    const double n = norm(d);
    EXPECT_NEAR(second_invariant(d), -n * n, 1e-12 * n * n);  // [YS] Eq. 9
  }
}

TEST(RheologyInvariants, FirstInvariantIsTheTrace) {
  // A stress of pressure 2500 Pa plus a traceless part: I_1 = trace = -3 p ([YS] Eq. 6).
  const SymmetricTensor t = isotropic_tensor(-2500.0) + SymmetricTensor{1.0, -3.0, 2.0, 4.0, 0, 0};
  EXPECT_DOUBLE_EQ(first_invariant(t), -3.0 * 2500.0);
  EXPECT_DOUBLE_EQ(-first_invariant(t) / 3.0, 2500.0);
}

TEST(RheologyInvariants, LodeAngleSignConvention) {
  // One negative, two positive principal rates: triaxial compression, theta = -30 deg ([YS]
  // Fig. 1, Table 1 row 1); two negative, one positive: extension, +30 deg.
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  EXPECT_DOUBLE_EQ(lode_angle(StrainRate{-a, b, b, 0, 0, 0}), -kSixthPi);
  EXPECT_DOUBLE_EQ(lode_angle(StrainRate{a, -b, -b, 0, 0, 0}), kSixthPi);
  EXPECT_EQ(lode_angle(StrainRate{-1, 0, 1, 0, 0, 0}), 0.0);
  // True triaxial compression lies in between.
  const double theta = lode_angle(StrainRate{-1.0, 0.3, 0.7, 0, 0, 0});
  EXPECT_LT(theta, 0.0);
  EXPECT_GT(theta, -kSixthPi);
}

TEST(RheologyInvariants, LodeAngleReachesThirtyDegreesExactlyWithoutNaN) {
  // Round-off pushes the arcsin argument of Eq. 12 past +-1 for some rotations of the triaxial
  // states; the clamp keeps theta at exactly +-30 deg.
  std::mt19937_64 rng(3);
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  for (int i = 0; i < 2000; ++i) {
    const auto q = testing::random_rotation(rng);
    const double compression = lode_angle(testing::rotate(StrainRate{-a, b, b, 0, 0, 0}, q));
    const double extension = lode_angle(testing::rotate(StrainRate{a, -b, -b, 0, 0, 0}, q));
    ASSERT_FALSE(std::isnan(compression));
    ASSERT_FALSE(std::isnan(extension));
    EXPECT_NEAR(compression, -kSixthPi, 1e-6);  // asin is steep at +-1: sqrt(eps) accuracy
    EXPECT_NEAR(extension, kSixthPi, 1e-6);
    EXPECT_GE(compression, -kSixthPi);
    EXPECT_LE(extension, kSixthPi);
  }
}

TEST(RheologyInvariants, LodeAngleIsRotationAndScaleInvariant) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 500; ++i) {
    const StrainRate d = testing::random_traceless_strain_rate(rng);
    const double theta = lode_angle(d);
    EXPECT_NEAR(lode_angle(testing::rotate(d, testing::random_rotation(rng))), theta, 1e-9);
    EXPECT_NEAR(lode_angle(1e-6 * d), theta, 1e-12);
    EXPECT_NEAR(lode_angle(1e6 * d), theta, 1e-12);
  }
}

TEST(RheologyInvariants, PlanarFlowIsIsochoricShear) {
  // 2D planar, incompressible: D_zz = 0 makes det(D) = 0, so theta = 0 ([YS] Sec. 4).
  EXPECT_EQ(lode_angle(planar_strain_rate(0.7, -0.7, 0.3)), 0.0);
  EXPECT_NEAR(norm(planar_strain_rate(0.7, -0.7, 0.3)), std::sqrt(0.49 + 0.09), 1e-15);
}

TEST(RheologyInvariants, AxisymmetricHoopRateEntersAsThirdDirection) {
  // Radial spreading of a collapsing cylinder: u_r = r, u_z = -2z gives D_rr = 1, D_zz = -2 and
  // D_thth = u_r/r = 1: one negative and two positive rates, triaxial compression. [YS] Sec. 4.2
  // finds only negative Lode angles in cylinder collapses.
  const StrainRate d = axisymmetric_strain_rate(1.0, -2.0, 0.0, 1.0);
  EXPECT_EQ(d.zz, 1.0);
  EXPECT_EQ(d.yy, -2.0);
  EXPECT_NEAR(lode_angle(d), -kSixthPi, 1e-12);
}

TEST(RheologyInvariants, DeviatoricPartIsUsedForTheDeformationState) {
  // A small spurious divergence does not count as shear: a pure expansion has ||dev D|| = 0.
  const DeformationState state = deformation_state(isotropic_tensor(1e-3));
  EXPECT_EQ(state.strain_rate_norm, 0.0);
  EXPECT_EQ(state.sin_three_lode, 0.0);
}

TEST(RheologyInvariants, NonFiniteStrainRateGivesDefinedState) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const DeformationState s_nan = deformation_state(StrainRate{nan, 0, 0, 0, 0, 0});
  EXPECT_EQ(s_nan.strain_rate_norm, 0.0);
  EXPECT_EQ(s_nan.sin_three_lode, 0.0);
  const DeformationState s_inf = deformation_state(StrainRate{0, 0, 0, inf, 0, 0});
  EXPECT_FALSE(std::isnan(s_inf.strain_rate_norm));
  EXPECT_FALSE(std::isnan(s_inf.sin_three_lode));
  EXPECT_EQ(lode_angle(StrainRate{}), 0.0);
}

TEST(RheologyInvariants, PrincipalValuesOfRotatedTensor) {
  std::mt19937_64 rng(13);
  for (int i = 0; i < 200; ++i) {
    const auto q = testing::random_rotation(rng);
    const auto values = principal_values(testing::rotate(SymmetricTensor{-3, 1.5, 1.5, 0, 0, 0}, q));
    EXPECT_NEAR(values[0], -3.0, 1e-13);
    EXPECT_NEAR(values[1], 1.5, 1e-13);
    EXPECT_NEAR(values[2], 1.5, 1e-13);
  }
}

}  // namespace
}  // namespace granflow::rheology

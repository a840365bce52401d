// A wall's Coulomb friction against the soil (models/rheology/wall_friction.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "models/rheology/invariants.hpp"
#include "models/rheology/wall_friction.hpp"

namespace granflow::rheology {
namespace {

TEST(WallFriction, StrengthIsAdhesionPlusFrictionTimesThePressureClippedAtZero) {
  const WallFriction wall = WallFriction::from_angle(20.0, 5.0);
  EXPECT_DOUBLE_EQ(wall.friction_coefficient, std::tan(20.0 * std::numbers::pi / 180.0));
  EXPECT_DOUBLE_EQ(wall.shear_strength(100.0), 5.0 + 100.0 * wall.friction_coefficient);
  EXPECT_EQ(wall.shear_strength(-100.0), 5.0);
  EXPECT_EQ(wall.shear_strength(std::nan("")), 5.0);
}

// The shear against a wall is the tangential part of D n: on a mesh of layers both of its components,
// whichever way the soil slides along the wall; the normal rate and the shear along the wall's own
// plane do not count.
TEST(WallFriction, ShearAgainstAWallIsTheTangentialPartOfTheRateOnItsNormal) {
  const StrainRate d{0.7, -0.2, -0.5, 3.0, 4.0, 12.0};  // xx yy zz xy xz yz
  EXPECT_DOUBLE_EQ(shear_against_wall(d, 0), 5.0);      // x-normal: xy, xz
  EXPECT_DOUBLE_EQ(shear_against_wall(d, 1), std::hypot(3.0, 12.0));
  EXPECT_DOUBLE_EQ(shear_against_wall(d, 2), std::hypot(4.0, 12.0));
  // The same shear turned within the wall's plane: the same value.
  const double turn = 0.3;
  const StrainRate turned{0.0, 0.0, 0.0, 0.0, 5.0 * std::cos(turn), 5.0 * std::sin(turn)};
  EXPECT_NEAR(shear_against_wall(turned, 2), 5.0, 1e-15);
  // Planar: |D_xy| exactly, on either wall; in simple shear it is ||dev D|| ([YS] Eq. 8).
  for (double shear : {-0.1234567, 2.5e-9, 7.0}) {
    const StrainRate planar = planar_strain_rate(0.0, 0.0, shear);
    EXPECT_EQ(shear_against_wall(planar, 0), std::abs(shear));
    EXPECT_EQ(shear_against_wall(planar, 1), std::abs(shear));
    EXPECT_DOUBLE_EQ(shear_against_wall(planar, 1), norm(planar));
  }
}

}  // namespace
}  // namespace granflow::rheology

// The momentum a cell starts a step with where the mixture's density is not conserved
// (models/mixture/carried_momentum.hpp): it keeps the kinetic energy the cell was carried with.
#include <gtest/gtest.h>

#include "models/mixture/carried_momentum.hpp"
#include "models/mixture/mixture_interpolation.hpp"

namespace granflow {
namespace {

TEST(CarriedMomentum, KeepsTheKineticEnergyItWasCarriedWith) {
  const double v = 1.7;
  for (const auto [density, carried] : {std::pair{1560.0, 1200.0}, {900.0, 1400.0}, {2650.0, 2650.0}, {1.0, 30.0}}) {
    const double momentum = mixture::carried_momentum_density(density, carried) * v;  // per volume
    const double velocity = momentum / density;  // what the step starts from
    EXPECT_NEAR(0.5 * density * velocity * velocity, 0.5 * carried * v * v, 1e-12 * carried * v * v);
  }
}

TEST(CarriedMomentum, IsTheCellsOwnWhereTheMassIsConserved) {
  for (const double rho : {1.0, 17.3, 2650.0}) EXPECT_NEAR(mixture::carried_momentum_density(rho, rho), rho, 1e-13 * rho);
}

TEST(CarriedMomentum, OutflowBeyondTheMassLeavesNone) {
  EXPECT_EQ(mixture::carried_momentum_density(1200.0, -3.0), 0.0);
  EXPECT_EQ(mixture::carried_momentum_density(1200.0, 0.0), 0.0);
}

// Why it is needed: the arctan mixture ([VoF] App. A, the paper's M and N) is concave above c = 0.07, so
// a fringe smeared over two cells weighs more than before: a cell 20 % full, spread over two, 59 % more. Kept at its velocity it would gain kinetic
// energy; carried, it keeps it.
TEST(CarriedMomentum, ASmearedFringeOfTheArctanMixtureGainsMassButNoEnergy) {
  const mixture::MixtureInterpolation arctan(mixture::InterpolationKind::arctan, -0.45, 25.0);
  const double rho_a = 1.0, rho_s = 2650.0, v = 1.0;
  const double before = arctan(0.2, rho_a, rho_s) + arctan(0.0, rho_a, rho_s);  // the fringe in one cell
  const double after = 2.0 * arctan(0.1, rho_a, rho_s);                            // the same soil over two
  EXPECT_GT(after, 1.5 * before);
  // Each of the two cells carried half the mass (the fluxes move the mass the fringe had) at v.
  const double carried = 0.5 * before;
  double kept_velocity = 0.0, carried_velocity = 0.0;
  for (int cell = 0; cell < 2; ++cell) {
    const double rho = 0.5 * after;
    kept_velocity += 0.5 * rho * v * v;
    const double u = mixture::carried_momentum_density(rho, carried) * v / rho;
    carried_velocity += 0.5 * rho * u * u;
  }
  EXPECT_GT(kept_velocity, 1.5 * 0.5 * before * v * v);               // energy from nowhere ...
  EXPECT_NEAR(carried_velocity, 0.5 * before * v * v, 1e-12 * before);  // ... and none
}

}  // namespace
}  // namespace granflow

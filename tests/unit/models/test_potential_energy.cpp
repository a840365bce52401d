// The mixture's potential energy density of the energy budget (models/mixture/potential_energy.hpp).
#include "models/mixture/potential_energy.hpp"

#include <gtest/gtest.h>

namespace granflow {
namespace {

// Soil at 0.3 m under gravity straight down has rho g h of it per unit volume, whatever the strip.
TEST(PotentialEnergy, UnderVerticalGravityItIsTheWeightTimesTheHeight) {
  const std::array<double, 3> g{0.0, -9.81, 0.0}, x{0.7, 0.3, 0.0};
  EXPECT_DOUBLE_EQ(mixture::potential_energy_density(2650.0, 1.0, g, x, false), 2650.0 * 9.81 * 0.3);
  EXPECT_DOUBLE_EQ(mixture::potential_energy_density(2650.0, 1.0, g, x, true), 2650.0 * 9.81 * 0.3);
}

// On a slope (gravity tilted by 24 deg along x): a closed domain counts the whole weight along x; a
// periodic strip only the soil's excess over the air, whose own weight the mean pressure gradient
// carries, so that air alone has no energy to release along the strip.
TEST(PotentialEnergy, AlongAPeriodicStripOnlyTheExcessOverTheAirCounts) {
  const std::array<double, 3> g{3.99, -8.96, 0.0}, x{0.05, 0.01, 0.0};
  const double soil = 1500.0, air = 1.2;
  EXPECT_DOUBLE_EQ(mixture::potential_energy_density(soil, air, g, x, false), -soil * (3.99 * 0.05 - 8.96 * 0.01));
  EXPECT_DOUBLE_EQ(mixture::potential_energy_density(soil, air, g, x, true),
                   -((soil - air) * 3.99 * 0.05 - soil * 8.96 * 0.01));
  EXPECT_DOUBLE_EQ(mixture::potential_energy_density(air, air, g, {0.05, 0.0, 0.0}, true), 0.0);
  // Gravity along z on a mesh of layers.
  EXPECT_DOUBLE_EQ(mixture::potential_energy_density(soil, air, {0.0, 0.0, -9.81}, {0.0, 0.0, 0.02}, true),
                   soil * 9.81 * 0.02);
}

}  // namespace
}  // namespace granflow

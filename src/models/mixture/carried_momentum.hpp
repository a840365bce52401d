#pragma once
// The momentum a cell carries from one step into the next where the mixture's density is not a
// conserved quantity. With the arctan interpolation ([VoF] App. A, Eqs. 21-26) a cell 10 % full weighs
// 59 % of the soil: the mass a step's fluxes leave in a cell, rho_carried V (its density before the
// step plus what flowed in less what flowed out), is not the density of its new soil fraction, rho(c) V,
// from which the next step starts. Kept at its velocity, the cell would gain (rho - rho_carried) V v^2 / 2
// of kinetic energy from nowhere where soil spreads (the interpolation is concave above c = 0.07: a cell
// 20 % full spread over two weighs 59 % more) and lose it where it gathers. Started with the momentum
// sqrt(rho rho_carried) v instead, it keeps the kinetic energy it was carried with:
// (sqrt(rho rho_carried) v)^2 / (2 rho) = rho_carried v^2 / 2. Where the mass is conserved (the linear
// mixture) the two densities agree and so does the momentum.
#include <algorithm>
#include <cmath>

namespace granflow::mixture {

// Momentum per unit velocity and volume, kg/m^3, that a cell of mixture density `density` starts a step
// with, its momentum having been carried over the last step with the density `carried_density` (a mass
// that outflow may have taken below zero where the two disagree: then none).
inline double carried_momentum_density(double density, double carried_density) {
  return std::sqrt(density * std::max(carried_density, 0.0));
}

}  // namespace granflow::mixture

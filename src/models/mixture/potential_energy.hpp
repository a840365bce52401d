#pragma once
// The potential energy of the mixture in the energy budget (the history's potential_energy and what
// the sides carry in, boundary_work): one formula for the cells' energy and the faces' flux.
#include <array>

namespace granflow::mixture {

// Potential energy per unit volume, J/m^3, of a mixture of density rho at position x under gravity g:
// -rho g.x. Along a periodic x (a strip whose ends are joined) the weight along x counted is the
// density's excess over the air's, (rho - rho_air) g_x: the air's own is carried by the mean pressure
// gradient, and the soil's first moment through the join is the budget's to add (soil_diagnostics.cpp).
inline double potential_energy_density(double rho, double rho_air, const std::array<double, 3>& g,
                                       const std::array<double, 3>& x, bool periodic_x) {
  if (periodic_x) return -((rho - rho_air) * g[0] * x[0] + rho * (g[1] * x[1] + g[2] * x[2]));
  return -rho * (g[0] * x[0] + g[1] * x[1] + g[2] * x[2]);
}

}  // namespace granflow::mixture

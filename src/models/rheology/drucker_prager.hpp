// Drucker-Prager yield surface calibrated to Mohr-Coulomb in isochoric shear, [YS] Eqs. 23-25.
#pragma once

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

// ||T_dev|| at yield: friction p, with friction = sin(phi) ([YS] Eq. 23) or mu(I) (Eq. 25).
constexpr double drucker_prager_yield_stress(double friction, double yield_pressure) noexcept {
  return friction * yield_pressure;
}

// f(T) = friction p - ||T_dev||, p = -I_1(T)/3, [YS] Eq. 23. Zero on the surface, positive inside.
double drucker_prager_yield_function(const SymmetricTensor& stress, double friction) noexcept;

}  // namespace granflow::rheology

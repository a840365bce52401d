// Drucker-Prager yield surface calibrated to Mohr-Coulomb in isochoric shear, [YS] Eqs. 23-25.
#pragma once

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

// ||T_dev|| at yield: friction p, with friction = sin(phi) ([YS] Eq. 23) or mu(I) (Eq. 25).
constexpr double drucker_prager_yield_stress(double friction, double yield_pressure) noexcept {
  return friction * yield_pressure;
}

// The same with a cohesion C, calibrated as the cone is to Mohr-Coulomb in isochoric shear
// (tau = C + sigma_n tan(phi) there): ||T_dev|| = sin(phi) p + C cos(phi), apex at p = -C cot(phi);
// at phi = 0 von Mises with the shear strength C.
constexpr double drucker_prager_yield_stress(double friction, double yield_pressure,
                                             double cohesion_cos_phi) noexcept {
  return friction * yield_pressure + cohesion_cos_phi;
}

// f(T) = friction p - ||T_dev||, p = -I_1(T)/3, [YS] Eq. 23. Zero on the surface, positive inside.
double drucker_prager_yield_function(const SymmetricTensor& stress, double friction) noexcept;

}  // namespace granflow::rheology

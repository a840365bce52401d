// Mohr-Coulomb yield surface with the von Mises plastic potential (alignment), [YS] Eqs. 26-28.
#pragma once

#include <cmath>
#include <numbers>

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

// ||T_dev|| / p on the Mohr-Coulomb surface in the direction of D, from [YS] Eq. 28:
//   eta = friction p / (2 ||D||) * sqrt3 / (sqrt3 cos(theta) + sin(theta) friction),
// i.e. ||T_dev|| / p = sqrt3 friction / (sqrt3 cos(theta) + sin(theta) friction).
// theta < 0 (compression) gives more than Drucker-Prager, theta > 0 less, theta = 0 equal.
inline double mohr_coulomb_stress_ratio(double friction, double lode_angle) noexcept {
  return std::numbers::sqrt3 * friction /
         (std::numbers::sqrt3 * std::cos(lode_angle) + std::sin(lode_angle) * friction);
}

inline double mohr_coulomb_yield_stress(double friction, double lode_angle,
                                        double yield_pressure) noexcept {
  return mohr_coulomb_stress_ratio(friction, lode_angle) * yield_pressure;
}

// f(T) = (sigma_1 - sigma_3) / (sigma_1 + sigma_3) - friction, [YS] Eq. 26, written with the
// principal stresses in the compression-positive convention of soil mechanics
// (sigma_1 = -T_min the major, sigma_3 = -T_max the minor principal stress). Evaluated from the
// eigenvalues of T, independently of the Lode-angle form Eq. 27 from which Eq. 28 derives
// (Eq. 27 as printed carries a sign slip in its sin(theta) term relative to Eq. 28).
// Zero on the surface, negative inside.
double mohr_coulomb_yield_function(const SymmetricTensor& stress, double friction);

}  // namespace granflow::rheology

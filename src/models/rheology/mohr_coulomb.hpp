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

// The same over Drucker-Prager's friction p ([YS] Eq. 24): the stress ratio of [YS] Fig. 8,
// sqrt3 / (sqrt3 cos(theta) + sin(theta) friction), also at friction = 0.
inline double mohr_coulomb_ratio_to_drucker_prager(double friction, double lode_angle) noexcept {
  return std::numbers::sqrt3 / (std::numbers::sqrt3 * std::cos(lode_angle) + std::sin(lode_angle) * friction);
}

inline double mohr_coulomb_yield_stress(double friction, double lode_angle,
                                        double yield_pressure) noexcept {
  return mohr_coulomb_stress_ratio(friction, lode_angle) * yield_pressure;
}

// The same with a cohesion C: the classical tau = C + sigma_n tan(phi), i.e. [YS] Eq. 26 as
// (sigma_1 - sigma_3) / 2 = (sigma_1 + sigma_3) / 2 sin(phi) + C cos(phi), in the direction of D:
//   ||T_dev|| = sqrt3 (friction p + C cos(phi)) / (sqrt3 cos(theta) + sin(theta) friction),
// friction = sin(phi). The cone's apex moves from p = 0 to p = -C cot(phi); at phi = 0 it is
// Tresca, ||T_dev|| = C / cos(theta).
inline double mohr_coulomb_yield_stress(double friction, double lode_angle, double yield_pressure,
                                        double cohesion_cos_phi) noexcept {
  return std::numbers::sqrt3 * (friction * yield_pressure + cohesion_cos_phi) /
         (std::numbers::sqrt3 * std::cos(lode_angle) + std::sin(lode_angle) * friction);
}

// f(T) = (sigma_1 - sigma_3) / (sigma_1 + sigma_3) - friction, [YS] Eq. 26, written with the
// principal stresses in the compression-positive convention of soil mechanics
// (sigma_1 = -T_min the major, sigma_3 = -T_max the minor principal stress). Evaluated from the
// eigenvalues of T, independently of the Lode-angle form Eq. 27 from which Eq. 28 derives
// (Eq. 27 as printed carries a sign slip in its sin(theta) term relative to Eq. 28).
// Zero on the surface, negative inside.
double mohr_coulomb_yield_function(const SymmetricTensor& stress, double friction);

// [YS] Eq. 26 with a cohesion, in stress units so that phi = 0 (Tresca) is included:
//   f(T) = (sigma_1 - sigma_3) / 2 - (sigma_1 + sigma_3) / 2 sin(phi) - C cos(phi).
// Zero on the surface, negative inside.
double mohr_coulomb_yield_function(const SymmetricTensor& stress, double sin_phi,
                                   double cohesion_cos_phi);

}  // namespace granflow::rheology

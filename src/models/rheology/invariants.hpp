// Tensor invariants, the norm convention of [YS] and the Lode angle.
//
// Two norms meet in this library and must not be mixed up:
//   [YS] Eq. 8:       ||A|| = sqrt(tr(A^2) / 2)
//   [VoF] Eqs. 10-12: sqrt(2 e:e) for the strain rate e, which is 2 ||D||.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

// I_1(A) = tr(A), [YS] Eq. 5; for the stress, I_1(T) = -3p (Eq. 6).
constexpr double first_invariant(const SymmetricTensor& a) noexcept { return trace(a); }

// I_2(A) = (tr(A)^2 - tr(A^2)) / 2, [YS] Eq. 7.
constexpr double second_invariant(const SymmetricTensor& a) noexcept {
  const double tr = trace(a);
  return 0.5 * (tr * tr - double_contraction(a, a));
}

// I_3(A) = det(A), [YS] Eq. 11.
constexpr double third_invariant(const SymmetricTensor& a) noexcept { return determinant(a); }

// ||A|| = sqrt(tr(A^2) / 2), [YS] Eq. 8 (not the Frobenius norm). For a traceless tensor
// I_2 = -||A||^2 (Eqs. 9-10), and ||T_dev|| = sqrt(J_2) of [VoF] Eq. 7.
inline double norm(const SymmetricTensor& a) noexcept {
  return std::sqrt(0.5 * double_contraction(a, a));
}

// sqrt(2 e:e) of [VoF] Eqs. 10-12 (e: strain rate). Kept as its own function so the factor 2
// between the papers' norms is explicit where the Bingham model is written: it equals 2 ||D||.
inline double vof_strain_rate_magnitude(const StrainRate& e) noexcept {
  return std::sqrt(2.0 * double_contraction(e, e));
}

// The deformation measures the viscosity needs, computed from the deviatoric part of D so that a
// small discrete divergence of the velocity does not register as shear.
struct DeformationState {
  double strain_rate_norm;  // ||dev D||, [YS] Eq. 8, 1/s
  double sin_three_lode;    // sin(3 theta), the arcsin argument of [YS] Eq. 12, in [-1, 1]
};

// sin(3 theta) of the unit deviatoric direction n = dev D / ||dev D||:
// I_3(D)/2 (3/(-I_2(D)))^{3/2} = (3 sqrt 3 / 2) det(n). Normalising first avoids overflow and
// underflow of ||D||^3. Clamped to [-1, 1] so theta = +-30 deg exactly is reached without a NaN
// from arcsin; NaN (from non-finite input) maps to 0.
inline double sin_three_lode_angle(const SymmetricTensor& deviator, double deviator_norm) noexcept {
  if (!(deviator_norm > 0.0)) return 0.0;
  const double s = 1.5 * std::numbers::sqrt3 * determinant((1.0 / deviator_norm) * deviator);
  if (std::isnan(s)) return 0.0;
  return std::clamp(s, -1.0, 1.0);
}

// A NaN strain rate is taken as rest (norm 0): the caller always gets a defined state.
inline DeformationState deformation_state(const StrainRate& d) noexcept {
  const SymmetricTensor dev = deviatoric(d);
  double n = norm(dev);
  if (std::isnan(n)) n = 0.0;
  return {n, sin_three_lode_angle(dev, n)};
}

// Lode angle theta in radians, [YS] Eq. 12, in [-pi/6, pi/6]. Negative for (true) triaxial
// compression (one negative, two positive principal strain rates), zero for isochoric shear,
// positive for triaxial extension ([YS] Fig. 1 and Table 1). Zero for D = 0.
inline double lode_angle_from_sin3(double sin_three_lode) noexcept {
  return std::asin(sin_three_lode) / 3.0;
}

inline double lode_angle(const StrainRate& d) noexcept {
  return lode_angle_from_sin3(deformation_state(d).sin_three_lode);
}

constexpr double degrees_to_radians(double degrees) noexcept {
  return degrees * std::numbers::pi / 180.0;
}
constexpr double radians_to_degrees(double radians) noexcept {
  return radians * 180.0 / std::numbers::pi;
}

}  // namespace granflow::rheology

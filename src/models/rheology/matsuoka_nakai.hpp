// Matsuoka-Nakai yield surface with the von Mises plastic potential (alignment), [YS] Eqs. 29-34.
//
// Derivation used for the viscosity. With alignment T = -p I + q n, n = dev D / ||D|| (so
// ||n|| = 1, I_2(n) = -1, det n = 2 sin(3 theta) / (3 sqrt 3)) and q = ||T_dev||, the invariants
// of T are I_1 = -3p, I_2 = 3p^2 - q^2, I_3 = -p^3 + p q^2 + q^3 det n. Eq. 29 then becomes, with
// the stress ratio x = q / p,
//     k det(n) x^3 + (k - 3) x^2 - (k - 9) = 0,
// and w = 1/x solves the depressed cubic w^3 - A w - B = 0, A = (k-3)/(k-9), B = k det(n)/(k-9).
// The yield surface is the largest root w (smallest positive x):
//     w = 2 sqrt(A/3) cos(arccos(r)/3),  r = k sin(3 theta) sqrt(k-9) / (k-3)^{3/2},
// where |r| <= 1 for every k > 9, so the root is always real. This is Eqs. 30-33 rewritten:
// z = 2 eta / p = x / ||D|| solves z^3 + a z^2 + b = 0 with a, b of Eqs. 31-32. Unlike the
// printed form it has no 1/I_3(D) singularity near isochoric shear and no quadrant ambiguity.
//
// Eq. 30 branch resolution (the printed text calls branch 1 "true triaxial extension"): the
// theta ranges of Eq. 30 are the right ones and the labels are swapped. Branch 1
// (-30 <= theta < 0) is (true) triaxial compression, consistent with [YS] Fig. 1 and with
// Table 1, where the TXC row has theta = -30 and MN above DP. Branch 1 only reproduces Table 1
// if gamma of Eq. 33 is taken in [0, 20] degrees, i.e.
//     3 gamma = atan2(3 sqrt(-3 (4 a^3 b + 27 b^2)), -2 a^3 - 27 b);
// the principal-value arctan of the printed ratio gives eta ||D|| / p = 0.275 instead of 0.380
// at TXC. See matsuoka_nakai_viscosity_eq30 below, kept as the paper's form for cross-checks.
#pragma once

#include <algorithm>
#include <cmath>

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

// k_MN fitted to Mohr-Coulomb and Drucker-Prager in isochoric shear, [YS] Eq. 34 (default):
// k = (9 - 3 friction^2) / (1 - friction^2), friction = sin(phi) or mu(I).
constexpr double matsuoka_nakai_k_isochoric(double friction) noexcept {
  const double f2 = friction * friction;
  return (9.0 - 3.0 * f2) / (1.0 - f2);
}

// k_MN fitted to Mohr-Coulomb in triaxial compression and extension (theta = +-30 deg), the
// "usual" choice mentioned in [YS] Sec. 2.3: k = (9 - friction^2) / (1 - friction^2).
constexpr double matsuoka_nakai_k_triaxial(double friction) noexcept {
  const double f2 = friction * friction;
  return (9.0 - f2) / (1.0 - f2);
}

// The cubic's coefficients for one k_MN (> 9), precomputed once for a constant friction angle.
struct MatsuokaNakai {
  double k_mn;               // k_MN, [YS] Eq. 29
  double isochoric_ratio;    // sqrt((k-9)/(k-3)), [YS] Eq. 30 third branch (||T_dev||/p)
  double root_scale;         // 2 sqrt(A/3)
  double lode_coefficient;   // r / sin(3 theta) = k sqrt(k-9) / (k-3)^{3/2}

  static MatsuokaNakai from_k(double k_mn) noexcept {
    const double km3 = k_mn - 3.0;
    const double km9 = k_mn - 9.0;
    return {k_mn, std::sqrt(km9 / km3), 2.0 * std::sqrt(km3 / (3.0 * km9)),
            k_mn * std::sqrt(km9) / (km3 * std::sqrt(km3))};
  }

  // ||T_dev|| / p on the surface in the direction of D (see the derivation above).
  [[nodiscard]] double stress_ratio(double sin_three_lode) const noexcept {
    if (sin_three_lode == 0.0) return isochoric_ratio;  // Eq. 30, third branch: I_3(D) = 0
    const double r = std::clamp(lode_coefficient * sin_three_lode, -1.0, 1.0);
    return 1.0 / (root_scale * std::cos(std::acos(r) / 3.0));
  }

  [[nodiscard]] double yield_stress(double sin_three_lode, double yield_pressure) const noexcept {
    return stress_ratio(sin_three_lode) * yield_pressure;
  }

  // With a cohesion C: the cone's apex moved from p = 0 to p = -attraction, attraction = C cot(phi),
  // as Mohr-Coulomb's tau = C + sigma_n tan(phi) moves it (Eq. 29 of the stress T - attraction I).
  [[nodiscard]] double yield_stress(double sin_three_lode, double yield_pressure,
                                    double attraction) const noexcept {
    return stress_ratio(sin_three_lode) * (yield_pressure + attraction);
  }
};

// [YS] Eqs. 30-33 as printed, with the branch and gamma resolution described above: eta for the
// strain rate D (its deviatoric part is used) and pressure p. Loses accuracy as I_3(D) -> 0
// (a, b ~ 1/I_3); the library evaluates the equivalent MatsuokaNakai::stress_ratio instead.
double matsuoka_nakai_viscosity_eq30(const StrainRate& strain_rate, double pressure, double k_mn);

// f(T) = I_1(T) I_2(T) / I_3(T) - k_MN, [YS] Eq. 29. Zero on the surface, negative inside the
// cone (f = 9 - k_MN on the hydrostatic axis).
double matsuoka_nakai_yield_function(const SymmetricTensor& stress, double k_mn) noexcept;

}  // namespace granflow::rheology

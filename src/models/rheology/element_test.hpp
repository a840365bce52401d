// The element test of [YS] Sec. 3 / Table 1: stresses of Drucker-Prager, Mohr-Coulomb and
// Matsuoka-Nakai for triaxial compression, isochoric shear and triaxial extension.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "models/rheology/parameters.hpp"
#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

enum class Deformation { triaxial_compression, isochoric_shear, triaxial_extension };

// "TXC", "SHR", "TXE" as in [YS] Fig. 3.
std::string_view abbreviation(Deformation deformation) noexcept;
// "DP", "MC", "MN" as in [YS] Table 1.
std::string_view abbreviation(YieldSurface surface) noexcept;

// The strain rates of Table 1 with ||D|| = 1: diag(-2, 1, 1)/sqrt3, diag(-1, 0, 1) and
// diag(2, -1, -1)/sqrt3. The table prints them rounded (-1.155, 0.577, 0.577), which would not
// be exactly traceless nor reach theta = -30 deg exactly.
StrainRate element_test_strain_rate(Deformation deformation) noexcept;

struct ElementTestRow {
  Deformation deformation;
  double lode_angle_deg;       // theta, [YS] Eq. 12
  YieldSurface model;
  double eta_norm_d_over_p;    // eta ||D|| / p
  double norm_tdev_over_p;     // ||T_dev|| / p = 2 eta ||D|| / p
  double relative;             // ||T_dev|| relative to Drucker-Prager for the same deformation
};

// Nine rows (TXC, SHR, TXE) x (DP, MC, MN), unregularised, k_MN from [YS] Eq. 34.
// Throws std::invalid_argument unless 0 < phi_deg < 90.
std::vector<ElementTestRow> element_test(double phi_deg = 36.5);

// The rows as an aligned text table, or as CSV with the header
// deformation,theta_deg,model,eta_norm_D_over_p,norm_Tdev_over_p,relative
std::string format_element_test(double phi_deg = 36.5, bool csv = false);

}  // namespace granflow::rheology

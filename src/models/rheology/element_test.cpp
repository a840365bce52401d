#include "models/rheology/element_test.hpp"

#include <array>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "models/rheology/drucker_prager.hpp"
#include "models/rheology/invariants.hpp"
#include "models/rheology/matsuoka_nakai.hpp"
#include "models/rheology/mohr_coulomb.hpp"
#include "models/rheology/regularisation.hpp"

namespace granflow::rheology {

std::string_view abbreviation(Deformation deformation) noexcept {
  switch (deformation) {
    case Deformation::triaxial_compression: return "TXC";
    case Deformation::isochoric_shear: return "SHR";
    case Deformation::triaxial_extension: return "TXE";
  }
  return "?";
}

std::string_view abbreviation(YieldSurface surface) noexcept {
  switch (surface) {
    case YieldSurface::drucker_prager: return "DP";
    case YieldSurface::mohr_coulomb: return "MC";
    case YieldSurface::matsuoka_nakai: return "MN";
  }
  return "?";
}

StrainRate element_test_strain_rate(Deformation deformation) noexcept {
  constexpr double major = 2.0 / std::numbers::sqrt3;  // 1.155
  constexpr double minor = 1.0 / std::numbers::sqrt3;  // 0.577
  switch (deformation) {
    case Deformation::triaxial_compression: return {-major, minor, minor, 0.0, 0.0, 0.0};
    case Deformation::isochoric_shear: return {-1.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    case Deformation::triaxial_extension: return {major, -minor, -minor, 0.0, 0.0, 0.0};
  }
  return {};
}

std::vector<ElementTestRow> element_test(double phi_deg) {
  if (!(phi_deg > 0.0 && phi_deg < 90.0)) {
    throw std::invalid_argument(
        fmt::format("element test: friction angle phi = {} must lie in (0, 90) degrees", phi_deg));
  }
  const double friction = std::sin(degrees_to_radians(phi_deg));
  const MatsuokaNakai matsuoka_nakai = MatsuokaNakai::from_k(matsuoka_nakai_k_isochoric(friction));
  constexpr double pressure = 1.0;  // everything is reported relative to p

  std::vector<ElementTestRow> rows;
  rows.reserve(9);
  for (Deformation deformation : {Deformation::triaxial_compression, Deformation::isochoric_shear,
                                  Deformation::triaxial_extension}) {
    const DeformationState state = deformation_state(element_test_strain_rate(deformation));
    const double theta = lode_angle_from_sin3(state.sin_three_lode);
    double drucker_prager_stress = 0.0;
    for (YieldSurface surface : {YieldSurface::drucker_prager, YieldSurface::mohr_coulomb,
                                 YieldSurface::matsuoka_nakai}) {
      double tau = 0.0;
      switch (surface) {
        case YieldSurface::drucker_prager:  // [YS] Eq. 24
          tau = drucker_prager_yield_stress(friction, pressure);
          break;
        case YieldSurface::mohr_coulomb:  // [YS] Eq. 28
          tau = mohr_coulomb_yield_stress(friction, theta, pressure);
          break;
        case YieldSurface::matsuoka_nakai:  // [YS] Eqs. 30-34
          tau = matsuoka_nakai.yield_stress(state.sin_three_lode, pressure);
          break;
      }
      const double eta = plastic_viscosity(tau, state.strain_rate_norm);
      const double eta_norm_d_over_p = eta * state.strain_rate_norm / pressure;
      const double norm_tdev_over_p = 2.0 * eta_norm_d_over_p;  // ||T_dev|| = 2 eta ||D||
      if (surface == YieldSurface::drucker_prager) drucker_prager_stress = norm_tdev_over_p;
      double theta_deg = radians_to_degrees(theta);
      if (theta_deg == 0.0) theta_deg = 0.0;  // no "-0" in the output
      rows.push_back({deformation, theta_deg, surface, eta_norm_d_over_p, norm_tdev_over_p,
                      norm_tdev_over_p / drucker_prager_stress});
    }
  }
  return rows;
}

std::string format_element_test(double phi_deg, bool csv) {
  const auto rows = element_test(phi_deg);
  std::string out;
  if (csv) {
    out += "deformation,theta_deg,model,eta_norm_D_over_p,norm_Tdev_over_p,relative\n";
    for (const auto& row : rows) {
      out += fmt::format("{},{:.6f},{},{:.6f},{:.6f},{:.6f}\n", abbreviation(row.deformation),
                         row.lode_angle_deg, abbreviation(row.model), row.eta_norm_d_over_p,
                         row.norm_tdev_over_p, row.relative);
    }
    return out;
  }
  out += fmt::format(
      "Element test (Rauter, Barker & Fellin 2020, Table 1), phi = {} deg, k_MN from Eq. 34\n",
      phi_deg);
  out += fmt::format("{:<11} {:>9} {:<5} {:>12} {:>11} {:>8}\n", "deformation", "theta", "model",
                     "eta|D|/p", "|Tdev|/p", "relative");
  for (const auto& row : rows) {
    out += fmt::format("{:<11} {:>9.3f} {:<5} {:>12.3f} {:>11.3f} {:>8.3f}\n",
                       abbreviation(row.deformation), row.lode_angle_deg, abbreviation(row.model),
                       row.eta_norm_d_over_p, row.norm_tdev_over_p, row.relative);
  }
  return out;
}

}  // namespace granflow::rheology

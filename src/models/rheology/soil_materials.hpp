// Several soils of one regularisation, each with its own rheology otherwise: yield surface, friction
// law, strength and density. Where soils share a cell or a face, the yield stress is the mean of
// theirs weighted by their shares of the soil there, regularised once ([VoF] Eq. 12): a mixture is as
// strong as its parts in proportion.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "models/rheology/granular_rheology.hpp"
#include "models/rheology/parameters.hpp"

namespace granflow::rheology {

class SoilMaterials {
 public:
  static constexpr int max_count = 16;  // materials, the base included
  // Shares of the soil at a point held by materials 1 .. count() - 1; material 0 (the base) holds the rest.
  using Shares = std::array<double, max_count - 1>;

  // Throws std::invalid_argument naming the material whose parameters are unusable or whose
  // regularisation is not the base's, or for more than max_count materials.
  SoilMaterials(const RheologyParameters& base, const std::vector<RheologyParameters>& others);

  [[nodiscard]] int count() const noexcept { return int(materials_.size()); }
  [[nodiscard]] const GranularRheology& material(int k) const noexcept { return materials_[k]; }

  // The stress ratio of the model's surface to Drucker-Prager's ([YS] Figs. 8, 11, 15) at a point whose
  // soil is shared out as `shares`: the share-weighted mean of the materials' own ratios (each depends
  // on its friction); 1 for the Drucker-Prager models and at rest.
  [[nodiscard]] double stress_ratio_to_drucker_prager(const StrainRate& strain_rate, double pressure,
                                                      const double* shares) const noexcept {
    double rest = 1.0, ratio = 0.0;
    for (int k = 1; k < count(); ++k) {
      const double share = std::clamp(shares[k - 1], 0.0, 1.0);
      if (share == 0.0) continue;
      ratio += share * materials_[k].stress_ratio_to_drucker_prager(strain_rate, pressure);
      rest -= share;
    }
    if (rest > 0.0) ratio += rest * materials_[0].stress_ratio_to_drucker_prager(strain_rate, pressure);
    return ratio;
  }

  // eta at a point whose soil is shared out as `shares` (count() - 1 entries, each clipped to [0, 1]).
  // With every share 0 it is the base's own dynamic_viscosity, to the bit.
  [[nodiscard]] double dynamic_viscosity(const StrainRate& strain_rate, double pressure,
                                         const double* shares) const noexcept {
    const auto [rate, tau] = rate_and_yield_stress(strain_rate, pressure, shares);
    return materials_[0].regularise(tau, rate);
  }

  // GranularRheology::relative_shear_stress of the shared-out soil: the stress of its viscosity over its
  // share-weighted yield stress (1 without strength).
  [[nodiscard]] double relative_shear_stress(const StrainRate& strain_rate, double pressure,
                                             const double* shares) const noexcept {
    const auto [rate, tau] = rate_and_yield_stress(strain_rate, pressure, shares);
    return tau > 0.0 ? 2.0 * materials_[0].regularise(tau, rate) * rate / tau : 1.0;
  }

 private:
  // ||dev D|| (0 for a NaN rate) and the yield stress, the mean of the materials' weighted by their shares.
  [[nodiscard]] std::pair<double, double> rate_and_yield_stress(const StrainRate& strain_rate, double pressure,
                                                                const double* shares) const noexcept {
    const SymmetricTensor dev = deviatoric(strain_rate);
    double rate = norm(dev);
    if (std::isnan(rate)) rate = 0.0;
    const double sin3 = needs_lode_angle_ ? sin_three_lode_angle(dev, rate) : 0.0;
    double rest = 1.0, tau = 0.0;
    for (int k = 1; k < count(); ++k) {
      const double share = std::clamp(shares[k - 1], 0.0, 1.0);
      if (share == 0.0) continue;
      tau += share * materials_[k].yield_stress_at(rate, sin3, pressure);
      rest -= share;
    }
    if (rest > 0.0) tau += rest * materials_[0].yield_stress_at(rate, sin3, pressure);
    return {rate, tau};
  }

  std::vector<GranularRheology> materials_;
  bool needs_lode_angle_ = false;  // some material's surface depends on the Lode angle
};

}  // namespace granflow::rheology

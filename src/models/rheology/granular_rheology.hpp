// The granular viscosity evaluated per cell: a value type built once from RheologyParameters,
// dispatching on enums (no virtual calls, no allocation per call).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/rheology/drucker_prager.hpp"
#include "models/rheology/drucker_prager_bingham.hpp"
#include "models/rheology/invariants.hpp"
#include "models/rheology/matsuoka_nakai.hpp"
#include "models/rheology/mohr_coulomb.hpp"
#include "models/rheology/mu_of_i.hpp"
#include "models/rheology/parameters.hpp"
#include "models/rheology/regularisation.hpp"
#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

struct RheologyResult {
  double dynamic_viscosity;    // eta, Pa s (never NaN, infinite or negative)
  double kinematic_viscosity;  // nu = eta / rho_s, m^2/s
  double strain_rate_norm;     // ||dev D||, [YS] Eq. 8, 1/s
  double lode_angle;           // theta, [YS] Eq. 12, radians in [-pi/6, pi/6]
  double yield_pressure;       // p as it enters the yield stress: clipped at zero, Pa
  double friction;             // sin(phi) or mu(I); 3 alpha_phi for drucker_prager_bingham
  double yield_stress;         // ||T_dev|| = sqrt(J_2) at yield, Pa
};

// Deviatoric stress T_dev = 2 eta dev(D), [YS] Eq. 16 / [VoF] Eq. 6.
constexpr SymmetricTensor deviatoric_stress(const StrainRate& strain_rate, double viscosity) noexcept {
  return (2.0 * viscosity) * deviatoric(strain_rate);
}

// Pressure entering a yield stress: clipped at zero (no tensile strength beyond k_c), NaN taken
// as zero, and capped far above any physical value so that products stay finite.
constexpr double yield_pressure(double pressure) noexcept {
  constexpr double max_pressure = 1e250;
  return pressure > 0.0 ? (pressure < max_pressure ? pressure : max_pressure) : 0.0;
}

class GranularRheology {
 public:
  // Throws std::invalid_argument with the message of validate() for unusable parameters.
  explicit GranularRheology(const RheologyParameters& parameters);

  // Everything at one point. Edge cases: D = 0 gives the regularised maximum (m tau_y + mu_min,
  // or eta_max when tau_y > 0); a NaN strain rate counts as rest; p <= 0 or NaN as p = 0.
  [[nodiscard]] RheologyResult evaluate(const StrainRate& strain_rate,
                                        double pressure) const noexcept {
    const DeformationState state = deformation_state(strain_rate);
    const double p = yield_pressure(pressure);
    const double friction = friction_coefficient(state.strain_rate_norm, p);
    const double tau = yield_stress(friction, state.sin_three_lode, p);
    const double eta = regularise(tau, state.strain_rate_norm);
    return {eta,
            eta * inverse_density_,
            state.strain_rate_norm,
            lode_angle_from_sin3(state.sin_three_lode),
            p,
            model_ == Model::drucker_prager_bingham ? 3.0 * bingham_.alpha_phi : friction,
            tau};
  }

  // The viscosity alone, for hot loops: skips the Lode angle where the surface does not need it.
  [[nodiscard]] double dynamic_viscosity(const StrainRate& strain_rate,
                                         double pressure) const noexcept {
    const SymmetricTensor dev = deviatoric(strain_rate);
    double rate = norm(dev);
    if (std::isnan(rate)) rate = 0.0;
    const double sin3 = needs_lode_angle_ ? sin_three_lode_angle(dev, rate) : 0.0;
    const double p = yield_pressure(pressure);
    return regularise(yield_stress(friction_coefficient(rate, p), sin3, p), rate);
  }

  [[nodiscard]] double kinematic_viscosity(const StrainRate& strain_rate,
                                           double pressure) const noexcept {
    return dynamic_viscosity(strain_rate, pressure) * inverse_density_;
  }

  // The model's yield stress over Drucker-Prager's at the same strain rate and pressure: the stress
  // ratio of [YS] Figs. 8, 11 and 15. It depends on the Lode angle and the friction (1 at theta = 0,
  // where all surfaces are calibrated); exactly 1 for the Drucker-Prager models and at rest. Each
  // surface, a cohesion included, is its cohesionless cone at p + C cot(phi), so the ratio is that of
  // the cones, at the friction of the given state (mu(I) depends on the pressure).
  [[nodiscard]] double stress_ratio_to_drucker_prager(const StrainRate& strain_rate, double pressure) const noexcept {
    if (yield_surface_of(model_) == YieldSurface::drucker_prager) return 1.0;
    const DeformationState state = deformation_state(strain_rate);
    if (!(state.strain_rate_norm > 0.0)) return 1.0;
    const double friction = friction_coefficient(state.strain_rate_norm, yield_pressure(pressure));
    if (model_ == Model::mohr_coulomb)  // [YS] Eq. 28 over Eq. 24; 1 / cos(theta) at phi = 0 (Tresca)
      return mohr_coulomb_ratio_to_drucker_prager(friction, lode_angle_from_sin3(state.sin_three_lode));
    return matsuoka_nakai_for(friction).stress_ratio(state.sin_three_lode) / friction;  // phi > 0 (validate)
  }

  // The shear stress the viscosity gives over the strength, 2 eta ||D|| / tau_y ([YS] Eq. 8's norms): how
  // much of the strength the soil mobilises at this strain rate and pressure (geotechnical software's
  // "relative shear stress"). Below yield the regularised viscosity carries the stress that holds the
  // soil up at a creep rate, so the ratio is the load over the strength there: 1 - exp(-2 m ||D||) +
  // 2 mu_min ||D|| / tau_y under [VoF] Eq. 12, 1 where the soil yields (above 1 only by the floor's
  // share), 0 at rest. 1 where the soil has no strength (p <= 0 without cohesion).
  [[nodiscard]] double relative_shear_stress(const StrainRate& strain_rate, double pressure) const noexcept {
    const RheologyResult r = evaluate(strain_rate, pressure);
    return r.yield_stress > 0.0 ? 2.0 * r.dynamic_viscosity * r.strain_rate_norm / r.yield_stress : 1.0;
  }

  // sin(phi) for a constant friction angle, mu(I) otherwise ([YS] Eq. 25).
  [[nodiscard]] double friction_coefficient(double strain_rate_norm,
                                            double yield_pressure) const noexcept {
    if (friction_ == FrictionSource::constant) return sin_phi_;
    // I -> inf as p -> 0; the yield stress is zero there anyway, this only avoids 0/0.
    if (!(yield_pressure > 0.0)) return mu_of_i_.limiting_friction;
    return mu_of_i_.friction(
        inertial_number(strain_rate_norm, grain_diameter_, density_, yield_pressure));
  }

  // ||T_dev|| at yield for a deformation already reduced to its norm and sin(3 theta), at a pressure
  // not yet clipped: what several soils at one point each contribute (SoilMaterials).
  [[nodiscard]] double yield_stress_at(double strain_rate_norm, double sin_three_lode,
                                       double pressure) const noexcept {
    const double p = yield_pressure(pressure);
    return yield_stress(friction_coefficient(strain_rate_norm, p), sin_three_lode, p);
  }

  [[nodiscard]] bool needs_lode_angle() const noexcept { return needs_lode_angle_; }

  // ||T_dev|| at yield for the model's surface, given friction, sin(3 theta) and p >= 0.
  [[nodiscard]] double yield_stress(double friction, double sin_three_lode,
                                    double yield_pressure) const noexcept {
    double tau = 0.0;
    switch (model_) {
      case Model::drucker_prager_bingham:
        tau = bingham_.yield_stress(yield_pressure);  // [VoF] Eq. 7
        break;
      // A cohesion comes with a constant friction angle only (validate), so friction = sin(phi).
      case Model::drucker_prager:
        tau = drucker_prager_yield_stress(friction, yield_pressure, cohesion_cos_phi_);  // [YS] Eqs. 23-25
        break;
      case Model::mohr_coulomb:
        tau = mohr_coulomb_yield_stress(friction, lode_angle_from_sin3(sin_three_lode),
                                        yield_pressure, cohesion_cos_phi_);  // [YS] Eqs. 26, 28
        break;
      case Model::matsuoka_nakai:
        tau = matsuoka_nakai_for(friction).yield_stress(sin_three_lode, yield_pressure, attraction_);  // Eq. 30
        break;
    }
    return std::min(tau, max_yield_stress_);
  }

  // The chosen regularisation applied to tau_y at ||D||; finite and >= 0 for any tau_y >= 0.
  [[nodiscard]] double regularise(double yield_stress, double strain_rate_norm) const noexcept {
    const double eta =
        regularisation_ == Regularisation::exponential
            ? exponential_viscosity(yield_stress, strain_rate_norm, regularisation_time_,
                                    min_dynamic_viscosity_)
            : clipped_viscosity(yield_stress, strain_rate_norm, clip_min_viscosity_,
                                clip_max_viscosity_);
    return std::min(eta, std::numeric_limits<double>::max());
  }

  [[nodiscard]] const RheologyParameters& parameters() const noexcept { return parameters_; }
  [[nodiscard]] YieldSurface yield_surface() const noexcept { return yield_surface_of(model_); }
  [[nodiscard]] const DruckerPragerBingham& drucker_prager_bingham() const noexcept {
    return bingham_;
  }

 private:
  [[nodiscard]] MatsuokaNakai matsuoka_nakai_for(double friction) const noexcept {
    if (friction_ == FrictionSource::constant) return matsuoka_nakai_;
    return MatsuokaNakai::from_k(mn_fit_ == MatsuokaNakaiFit::isochoric_shear
                                     ? matsuoka_nakai_k_isochoric(friction)
                                     : matsuoka_nakai_k_triaxial(friction));
  }

  static constexpr double max_yield_stress_ = 1e280;  // keeps m * tau_y from reaching NaN

  RheologyParameters parameters_;
  Model model_;
  FrictionSource friction_;
  Regularisation regularisation_;
  MatsuokaNakaiFit mn_fit_;
  bool needs_lode_angle_;
  double sin_phi_;
  double cohesion_cos_phi_;  // C cos(phi): the [YS] surfaces' yield stress at p = 0 in isochoric shear
  double attraction_;        // C cot(phi): how far below p = 0 their apex lies (0 without cohesion)
  DruckerPragerBingham bingham_;
  MatsuokaNakai matsuoka_nakai_;
  MuOfI mu_of_i_;
  double grain_diameter_;
  double density_;
  double inverse_density_;
  double regularisation_time_;
  double min_dynamic_viscosity_;
  double clip_min_viscosity_;  // rho_s nu_min
  double clip_max_viscosity_;  // rho_s nu_max
};

}  // namespace granflow::rheology

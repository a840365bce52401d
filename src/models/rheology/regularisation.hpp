// From a yield stress to a finite viscosity. The plastic limit eta = tau_y / (2 ||D||) (from
// T_dev = 2 eta D, [YS] Eq. 16; Eqs. 11, 24, 25, 28, 30) is infinite at rest, so every model is
// regularised; the regularisation is chosen independently of the yield surface.
#pragma once

#include <cmath>

namespace granflow::rheology {

// Unregularised plastic viscosity tau_y / (2 ||D||): infinite for D = 0. For checks and the
// element test only; the solver uses one of the regularised forms below.
constexpr double plastic_viscosity(double yield_stress, double strain_rate_norm) noexcept {
  return yield_stress / (2.0 * strain_rate_norm);
}

// (1 - exp(-x)) / x, equal to 1 at x = 0 and 0 at x = inf, accurate for small x (expm1).
inline double relative_exponential_growth(double x) noexcept {
  return x > 0.0 ? -std::expm1(-x) / x : 1.0;
}

// Papanastasiou regularisation, [VoF] Eq. 12, with sqrt(2 e:e) = 2 ||D||:
//   eta = mu_min + tau_y / (2 ||D||) (1 - exp(-m 2 ||D||))
//       = mu_min + m tau_y (1 - exp(-x)) / x,  x = 2 m ||D||.
// At rest eta = mu_min + m tau_y: for Drucker-Prager-Bingham m (3 alpha_phi p + k_c) is the
// mu_max of [VoF] Sec. 2.
inline double exponential_viscosity(double yield_stress, double strain_rate_norm,
                                    double regularisation_time, double min_viscosity) noexcept {
  return min_viscosity + regularisation_time * yield_stress *
                             relative_exponential_growth(2.0 * regularisation_time * strain_rate_norm);
}

// Clipping of the plastic viscosity to [eta_min, eta_max] ([YS] Sec. 2.4 and 4, where it is
// written for the kinematic viscosity nu = eta / rho in [1e-5, 1] m^2/s). Ordered so that D = 0
// gives eta_max when the material has strength and eta_min when it has none, without 0/0.
inline double clipped_viscosity(double yield_stress, double strain_rate_norm, double min_viscosity,
                                double max_viscosity) noexcept {
  if (!(yield_stress > 0.0)) return min_viscosity;
  const double twice_rate = 2.0 * strain_rate_norm;
  if (yield_stress >= twice_rate * max_viscosity) return max_viscosity;
  const double eta = yield_stress / twice_rate;
  return eta > min_viscosity ? eta : min_viscosity;
}

}  // namespace granflow::rheology

// The mu(I) friction law of Jop, Forterre & Pouliquen (2006), used in place of sin(phi) in any of
// the yield surfaces ([YS] Eq. 25 and Sec. 6).
#pragma once

#include <cmath>

namespace granflow::rheology {

// Inertial number I = gamma_dot d / sqrt(p / rho_s) with the shear rate gamma_dot = 2 ||D||
// (Jop et al. use |gamma_dot| = sqrt(2 D:D) = 2 ||D|| in the [YS] norm). Written as
// 2 ||D|| d sqrt(rho_s / p) so that it is +inf, not NaN, as p -> 0 with shear.
// Requires yield_pressure > 0.
inline double inertial_number(double strain_rate_norm, double grain_diameter, double density,
                              double yield_pressure) noexcept {
  return 2.0 * strain_rate_norm * grain_diameter * std::sqrt(density / yield_pressure);
}

struct MuOfI {
  double static_friction;            // mu_s
  double limiting_friction;          // mu_2
  double reference_inertial_number;  // I_0

  // mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1); mu_s at I = 0 and mu_2 at I = inf, no NaN at
  // either end (I_0 > 0).
  [[nodiscard]] double friction(double inertial) const noexcept {
    return static_friction +
           (limiting_friction - static_friction) / (reference_inertial_number / inertial + 1.0);
  }
};

}  // namespace granflow::rheology

// Drucker-Prager yield criterion in the parametrisation of [VoF] Sec. 2 (Eqs. 7-11), the basis of
// the regularised Bingham model of [VoF] Eq. 12.
#pragma once

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

struct DruckerPragerBingham {
  double alpha_phi;       // alpha_phi, [VoF] Eq. 8 (dimensionless)
  double cohesion_term;   // k_c, [VoF] Eq. 9 (Pa)

  // [VoF] Eqs. 8-9: alpha_phi = tan(phi) / sqrt(9 + 12 tan^2 phi),
  //                 k_c = 3 C / sqrt(9 + 12 tan^2 phi)  (plane-strain match to Mohr-Coulomb).
  static DruckerPragerBingham from_friction_angle(double friction_angle_rad, double cohesion);

  // Deviatoric stress norm at yield, sqrt(J_2) = ||T_dev|| = 3 alpha_phi p + k_c: [VoF] Eq. 7 with
  // I_1 = -3p. The pressure passed in is already clipped at zero by the caller.
  [[nodiscard]] double yield_stress(double yield_pressure) const noexcept {
    return 3.0 * alpha_phi * yield_pressure + cohesion_term;
  }

  // Phi(T) = sqrt(J_2) + alpha_phi I_1 - k_c, [VoF] Eq. 7 (the square root covers J_2 only; the
  // printed equation extends it over the whole expression, which is not a yield function).
  [[nodiscard]] double yield_function(const SymmetricTensor& stress) const noexcept;
};

}  // namespace granflow::rheology

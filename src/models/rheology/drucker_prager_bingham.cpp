#include "models/rheology/drucker_prager_bingham.hpp"

#include <cmath>

#include "models/rheology/invariants.hpp"

namespace granflow::rheology {

DruckerPragerBingham DruckerPragerBingham::from_friction_angle(double friction_angle_rad,
                                                              double cohesion) {
  const double tan_phi = std::tan(friction_angle_rad);
  const double denominator = std::sqrt(9.0 + 12.0 * tan_phi * tan_phi);
  return {tan_phi / denominator, 3.0 * cohesion / denominator};
}

double DruckerPragerBingham::yield_function(const SymmetricTensor& stress) const noexcept {
  const double sqrt_j2 = norm(deviatoric(stress));  // J_2 = tau:tau / 2 = ||T_dev||^2
  return sqrt_j2 + alpha_phi * first_invariant(stress) - cohesion_term;
}

}  // namespace granflow::rheology

#include "models/rheology/mohr_coulomb.hpp"

namespace granflow::rheology {

double mohr_coulomb_yield_function(const SymmetricTensor& stress, double friction) {
  const auto t = principal_values(stress);  // ascending, tension positive
  const double sigma_major = -t[0];
  const double sigma_minor = -t[2];
  return (sigma_major - sigma_minor) / (sigma_major + sigma_minor) - friction;
}

double mohr_coulomb_yield_function(const SymmetricTensor& stress, double sin_phi,
                                   double cohesion_cos_phi) {
  const auto t = principal_values(stress);
  const double sigma_major = -t[0];
  const double sigma_minor = -t[2];
  return 0.5 * (sigma_major - sigma_minor) - 0.5 * (sigma_major + sigma_minor) * sin_phi -
         cohesion_cos_phi;
}

}  // namespace granflow::rheology

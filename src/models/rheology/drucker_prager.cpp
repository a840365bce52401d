#include "models/rheology/drucker_prager.hpp"

#include "models/rheology/invariants.hpp"

namespace granflow::rheology {

double drucker_prager_yield_function(const SymmetricTensor& stress, double friction) noexcept {
  const double pressure = -first_invariant(stress) / 3.0;  // [YS] Eq. 6
  return friction * pressure - norm(deviatoric(stress));
}

}  // namespace granflow::rheology

#include "models/rheology/matsuoka_nakai.hpp"

#include <numbers>

#include "models/rheology/invariants.hpp"

namespace granflow::rheology {

double matsuoka_nakai_viscosity_eq30(const StrainRate& strain_rate, double pressure, double k_mn) {
  const SymmetricTensor d = deviatoric(strain_rate);
  const double i2 = second_invariant(d);
  const double i3 = third_invariant(d);
  if (i3 == 0.0) {  // Eq. 30, third branch (isochoric shear)
    return pressure / (2.0 * std::sqrt(-i2)) * std::sqrt((9.0 - k_mn) / (3.0 - k_mn));
  }
  const double a = i2 * (3.0 - k_mn) / (i3 * k_mn);  // Eq. 31
  const double b = (9.0 - k_mn) / (i3 * k_mn);        // Eq. 32
  const double a3 = a * a * a;
  const double discriminant = std::max(0.0, -3.0 * (4.0 * a3 * b + 27.0 * b * b));
  // Eq. 33 with gamma in [0, pi/3] (positive numerator, atan2 for the quadrant).
  const double gamma = std::atan2(3.0 * std::sqrt(discriminant), -2.0 * a3 - 27.0 * b) / 3.0;
  if (i3 < 0.0) {  // theta < 0: (true) triaxial compression, Eq. 30 first branch
    return pressure * a * (std::cos(gamma) - std::numbers::sqrt3 * std::sin(gamma) - 1.0) / 6.0;
  }
  return pressure * a * (2.0 * std::cos(gamma) - 1.0) / 6.0;  // theta > 0: extension, branch 2
}

double matsuoka_nakai_yield_function(const SymmetricTensor& stress, double k_mn) noexcept {
  return first_invariant(stress) * second_invariant(stress) / third_invariant(stress) - k_mn;
}

}  // namespace granflow::rheology

#include "models/mixture/mixture_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace granflow::mixture {

double MixtureInterpolation::operator()(double c, double air, double soil) const {
  c = std::clamp(c, 0.0, 1.0);
  if (kind == InterpolationKind::linear) return (1.0 - c) * air + c * soil;  // [VoF] Eq. 1
  const double pi = std::numbers::pi;
  const double jump = soil - air;
  const double eps0 = std::atan(-0.5 * N) / pi + 0.5;                                              // Eq. 23
  const double eps1 = 0.5 - std::atan(0.5 * N) / pi;                                               // Eq. 24
  const double delta0 = (std::atan(N * (-M - 0.5)) / pi + 0.5) - (1.0 + M) * eps0 - M * eps1;      // Eq. 25
  const double delta1 = std::abs(std::atan(N * (1.0 - M - 0.5)) / pi - M * eps0 - M * eps1 -
                                 std::atan(N * (1.0 - 0.5)) / pi);                                 // Eq. 26
  const double t_corr = M > 0.0 ? c * delta1 * jump : (M < 0.0 ? -c * delta1 * jump : 0.0);       // Eq. 22
  const double value = air + (std::atan(N * (c - M - 0.5)) / pi + 0.5) * jump                      // Eq. 21
                       - (1.0 - (c - M)) * eps0 * jump + (c - M) * eps1 * jump - (1.0 - c) * delta0 * jump + t_corr;
  // The correction terms make the end points exact up to round-off; clamp the remainder.
  return std::clamp(value, std::min(air, soil), std::max(air, soil));
}

bool parse_interpolation_kind(std::string_view name, InterpolationKind& out) {
  if (name == "linear") out = InterpolationKind::linear;
  else if (name == "arctan") out = InterpolationKind::arctan;
  else return false;
  return true;
}

}  // namespace granflow::mixture

#include "models/mixture/mixture_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace granflow::mixture {

MixtureInterpolation::MixtureInterpolation(InterpolationKind kind, double M, double N) : kind_(kind), M_(M), N_(N) {
  const double pi = std::numbers::pi;
  eps0_ = std::atan(-0.5 * N) / pi + 0.5;                                                        // Eq. 23
  eps1_ = 0.5 - std::atan(0.5 * N) / pi;                                                         // Eq. 24
  delta0_ = (std::atan(N * (-M - 0.5)) / pi + 0.5) - (1.0 + M) * eps0_ - M * eps1_;              // Eq. 25
  delta1_ = std::abs(std::atan(N * (1.0 - M - 0.5)) / pi - M * eps0_ - M * eps1_ -
                     std::atan(N * (1.0 - 0.5)) / pi);                                           // Eq. 26
}

double MixtureInterpolation::operator()(double c, double air, double soil) const {
  c = std::clamp(c, 0.0, 1.0);
  if (kind_ == InterpolationKind::linear) return (1.0 - c) * air + c * soil;  // [VoF] Eq. 1
  // Pure cells, most of the grid, take the phase's own value: Eqs. 25-26 make the end points exact
  // only up to round-off times the jump, 6e-10 Pa s on the air's 1.8e-5 against a soil of 1e8 Pa s.
  if (c == 0.0) return air;
  if (c == 1.0) return soil;
  const double pi = std::numbers::pi;
  const double jump = soil - air, M = M_, N = N_;
  const double t_corr = M > 0.0 ? c * delta1_ * jump : (M < 0.0 ? -c * delta1_ * jump : 0.0);  // Eq. 22
  const double value = air + (std::atan(N * (c - M - 0.5)) / pi + 0.5) * jump                   // Eq. 21
                       - (1.0 - (c - M)) * eps0_ * jump + (c - M) * eps1_ * jump - (1.0 - c) * delta0_ * jump + t_corr;
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

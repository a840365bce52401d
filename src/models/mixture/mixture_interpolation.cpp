#include "models/mixture/mixture_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace granflow::mixture {

namespace {

// The end-point corrections of the arctan interpolation, which depend on M and N only.
struct ArctanCorrections {
  double M = 0.0, N = 0.0;
  double eps0 = 0.0, eps1 = 0.0, delta0 = 0.0, delta1 = 0.0;
};

ArctanCorrections arctan_corrections(double M, double N) {
  const double pi = std::numbers::pi;
  ArctanCorrections k{M, N};
  k.eps0 = std::atan(-0.5 * N) / pi + 0.5;                                                        // Eq. 23
  k.eps1 = 0.5 - std::atan(0.5 * N) / pi;                                                         // Eq. 24
  k.delta0 = (std::atan(N * (-M - 0.5)) / pi + 0.5) - (1.0 + M) * k.eps0 - M * k.eps1;            // Eq. 25
  k.delta1 = std::abs(std::atan(N * (1.0 - M - 0.5)) / pi - M * k.eps0 - M * k.eps1 -
                      std::atan(N * (1.0 - 0.5)) / pi);                                           // Eq. 26
  return k;
}

// The corrections for (M, N), kept for the last two pairs seen: a run mixes density and viscosity,
// each with one pair, once per cell and face, and four of the five arctangents are these constants.
const ArctanCorrections& cached_corrections(double M, double N) {
  static ArctanCorrections cache[2] = {arctan_corrections(0.0, 1.0), arctan_corrections(0.0, 1.0)};
  static int next = 0;
  for (const auto& k : cache)
    if (k.M == M && k.N == N) return k;
  cache[next] = arctan_corrections(M, N);
  const int filled = next;
  next = 1 - next;
  return cache[filled];
}

}  // namespace

double MixtureInterpolation::operator()(double c, double air, double soil) const {
  c = std::clamp(c, 0.0, 1.0);
  if (kind == InterpolationKind::linear) return (1.0 - c) * air + c * soil;  // [VoF] Eq. 1
  // Pure cells, most of the grid, take the phase's own value: Eqs. 25-26 make the end points exact
  // only up to round-off times the jump, 6e-10 Pa s on the air's 1.8e-5 against a soil of 1e8 Pa s.
  if (c == 0.0) return air;
  if (c == 1.0) return soil;
  const double pi = std::numbers::pi;
  const double jump = soil - air;
  const ArctanCorrections& k = cached_corrections(M, N);
  const double eps0 = k.eps0, eps1 = k.eps1, delta0 = k.delta0, delta1 = k.delta1;
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

#pragma once
// Mixture properties from the soil fraction c: linear ([VoF] Eq. 1) or the arctan interpolation of
// [VoF] App. A (Eqs. 21-26), whose constants M and N shift and sharpen the transition so that
// interface cells keep more of the soil's viscosity (less creep at the surface).
#include <string_view>

namespace granflow::mixture {

enum class InterpolationKind { linear, arctan };

struct MixtureInterpolation {
  InterpolationKind kind = InterpolationKind::linear;
  double M = 0.0;  // shift of the transition ([VoF] Sec. 4.1: -0.45)
  double N = 1.0;  // steepness ([VoF] Sec. 4.1: 25)

  // Property of the mixture at soil fraction c (clamped to [0, 1]) between the air value and the soil
  // value.
  double operator()(double c, double air, double soil) const;
};

bool parse_interpolation_kind(std::string_view name, InterpolationKind& out);

}  // namespace granflow::mixture

#pragma once
// Mixture properties from the soil fraction c: linear ([VoF] Eq. 1) or the arctan interpolation of
// [VoF] App. A (Eqs. 21-26), whose constants M and N shift and sharpen the transition so that
// interface cells keep more of the soil's viscosity (less creep at the surface).
#include <string_view>

namespace granflow::mixture {

enum class InterpolationKind { linear, arctan };

class MixtureInterpolation {
 public:
  MixtureInterpolation() : MixtureInterpolation(InterpolationKind::linear, 0.0, 1.0) {}
  // M: shift of the transition ([VoF] Sec. 4.1: -0.45); N: its steepness (25). The linear form
  // reads neither.
  MixtureInterpolation(InterpolationKind kind, double M, double N);

  // Property of the mixture at soil fraction c (clamped to [0, 1]) between the air value and the soil
  // value.
  double operator()(double c, double air, double soil) const;

  InterpolationKind kind() const { return kind_; }
  double M() const { return M_; }
  double N() const { return N_; }

 private:
  InterpolationKind kind_;
  double M_, N_;
  // End-point corrections of the arctan form, Eqs. 23-26: constants of M and N, made once.
  double eps0_ = 0.0, eps1_ = 0.0, delta0_ = 0.0, delta1_ = 0.0;
};

bool parse_interpolation_kind(std::string_view name, InterpolationKind& out);

}  // namespace granflow::mixture

// Coulomb friction between a wall and the soil: a bed smoother (or rougher) than the soil itself, as a
// flume's glass or steel floor. The wall passes to the soil a shear stress of at most its strength,
//   tau_w = a + tan(delta) p,
// delta the wall's friction angle, a its adhesion and p the soil's pressure at the wall (its excess
// over the ambient pressure, clipped at zero as the rheology's). The soil slides on the wall where its
// shear stress there reaches tau_w; where the soil is the weaker, it yields inside and the wall holds.
// On the wall face the soil's viscosity is then at most tau_w / (2 |D_tn|), regularised as the rheology
// regularises tau_y / (2 ||D||) ([VoF] Eq. 12), D_tn the shear of the soil against the wall: in simple
// shear |D_tn| = ||dev D|| ([YS] Eq. 8), so the wall's shear stress 2 eta D_tn tends to tau_w once the
// soil slides (SoilPhase::update_face_viscosity).
#pragma once

#include <cmath>
#include <numbers>

#include "models/rheology/tensor.hpp"

namespace granflow::rheology {

struct WallFriction {
  double friction_coefficient = 0.0;   // tan(delta)
  double adhesion = 0.0;               // a, Pa
  double friction_angle_degrees = 0.0;  // delta as the case gives it, for messages

  static WallFriction from_angle(double friction_angle_degrees, double adhesion) noexcept {
    return {std::tan(friction_angle_degrees * std::numbers::pi / 180.0), adhesion, friction_angle_degrees};
  }

  // tau_w at the soil's pressure p at the wall (Pa); p below zero (or NaN) counts as zero.
  [[nodiscard]] constexpr double shear_strength(double pressure) const noexcept {
    return adhesion + friction_coefficient * (pressure > 0.0 ? pressure : 0.0);
  }
};

// |D_tn|, the soil's shear against a wall normal to `normal_axis` (0, 1, 2: x, y, z): the tangential
// part of D n, both of its components on a mesh of layers (the soil may slide along the wall in any
// direction). A planar or axisymmetric rate has no out-of-plane shear, and this is |D_xy| exactly.
[[nodiscard]] inline double shear_against_wall(const StrainRate& d, int normal_axis) noexcept {
  switch (normal_axis) {
    case 0: return std::hypot(d.xy, d.xz);
    case 1: return std::hypot(d.xy, d.yz);
    default: return std::hypot(d.xz, d.yz);
  }
}

}  // namespace granflow::rheology

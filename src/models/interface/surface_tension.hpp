#pragma once
// Surface tension of the soil-air (water-air) interface as a force on the cell faces: the continuum
// surface force of Brackbill, Kothe & Zemach (1992, J. Comput. Phys. 100:335), f = sigma kappa grad(c),
// in the balanced-force form of Francois et al. (2006, J. Comput. Phys. 213:141): on the face between
// cells P and N,
//   f_f = sigma kappa_f (c_N - c_P) / d_PN,
// the same difference of c across the face as the pressure's, so that a pressure jump sigma kappa
// across a resting interface balances it exactly. The curvature kappa = -div(n), n = grad(c~)/|grad(c~)|
// the unit normal of a smoothed fraction c~, positive where the soil side is convex (a drop).
// Pure functions of numbers; the stencils over the mesh are in solver/surface_tension_force.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace granflow::interface {

// The component along a face's normal of the unit normal n = g / |g|, from the gradient of c~ on the
// face: `along` the face's normal, `across1`, `across2` the two others (0 on a planar mesh). A face
// where c~ does not change has no normal: 0.
inline double unit_normal_component(double along, double across1, double across2) {
  const double magnitude = std::sqrt(along * along + across1 * across1 + across2 * across2);
  return magnitude > 0.0 ? along / magnitude : 0.0;
}

// kappa of a cell = -div(n) = -(1/V) sum_f n_f . a_f, from the outward normal components of n on its
// faces times their areas (`outward_flux_sum`); with the face areas and volume of an axisymmetric mesh,
// the hoop curvature -n_r / r comes with it.
inline double cell_curvature(double outward_flux_sum, double volume) { return -outward_flux_sum / volume; }

// The curvature on a face from its two cells', each weighted by |grad c~| there: a cell nearer the
// interface has the better-defined normal. A face with neither has none.
inline double face_curvature(double kappa_low, double weight_low, double kappa_high, double weight_high) {
  const double w = weight_low + weight_high;
  return w > 0.0 ? (weight_low * kappa_low + weight_high * kappa_high) / w : 0.0;
}

// f_f = sigma kappa_f (c_high - c_low) / d: N/m^3 along the face's normal (towards the high cell).
inline double surface_tension_face_force(double sigma, double kappa_face, double c_low, double c_high,
                                         double distance) {
  return sigma * kappa_face * (c_high - c_low) / distance;
}

// The capillary time-step limit of an explicit surface force (Brackbill et al. 1992):
// dt < sqrt(rho_mean h^3 / (2 pi sigma)), rho_mean the mean of the two phases' densities and h the
// smallest cell width; beyond it capillary waves of the shortest length grow.
inline double capillary_time_step(double density_a, double density_b, double h, double sigma) {
  if (sigma <= 0.0) return std::numeric_limits<double>::infinity();
  return std::sqrt(0.5 * (density_a + density_b) * h * h * h / (2.0 * std::numbers::pi * sigma));
}

// A wall's ghost of the smoothed fraction for a contact angle theta (through the soil, from the wall),
// m cells beyond the wall's first cell, whose c~ is `first` and whose gradient along the wall has the
// magnitude `along_wall`; h: the first cell's width across the wall. The unit normal n = grad(c~)/|grad(c~)|
// at the wall is then -cos(theta) n_w + sin(theta) t (n_w into the domain, t along the wall towards the
// soil), so the gradient across the wall is -cot(theta) |grad along the wall|: the ghost lies
// m h cot(theta) |grad along| above `first`, clipped to [0, 1]. theta = 90 deg is the mirror.
inline double contact_angle_ghost(double first, double along_wall, double h, int m, double cot_theta) {
  return std::clamp(first + m * h * cot_theta * along_wall, 0.0, 1.0);
}

// The 1-2-1 weights of the smoothing filter, by offset -1, 0, 1 along one axis.
inline double smoothing_weight(int offset) { return offset == 0 ? 0.5 : 0.25; }

}  // namespace granflow::interface

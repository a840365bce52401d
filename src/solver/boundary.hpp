#pragma once
// Boundary conditions of the flow, one per side of the box.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "mesh/grid.hpp"
#include "models/rheology/wall_friction.hpp"

namespace granflow {

enum class BoundaryKind {
  wall,        // no-slip; a non-zero wall velocity makes it a moving (sliding) wall
  slip,        // impermeable, free of shear
  atmosphere,  // fixed total pressure: outflow at the static pressure, inflow at p0 - rho|u|^2/2
  periodic,    // west and east joined (GridSpec::periodic_x): no boundary there
  inlet,       // a given velocity into the domain, carrying soil below a given depth and air above
};

struct BoundaryCondition {
  BoundaryKind kind = BoundaryKind::wall;
  // The velocity a wall slides at (tangential: its normal component is zero), or an inlet's inflow.
  std::array<double, 3> velocity{0.0, 0.0, 0.0};
  // A wall of its own Coulomb friction against the soil (models/rheology/wall_friction.hpp); without
  // it the soil's own strength is what holds it at the wall.
  std::optional<rheology::WallFriction> friction;
  double pressure = 0.0;                          // atmosphere: total pressure p0
  bool total_pressure = true;                     // false: p0 is the static pressure also for inflow
  // Soil fraction carried in by inflow through an atmosphere side or an inlet.
  double inflow_soil_fraction = 0.0;
  // Inlet on a side across x or z: its soil enters below this height above the domain's bottom (y
  // lower), air above it. Infinite: over the whole side.
  double inflow_soil_depth = std::numeric_limits<double>::infinity();
  // Inlet: the soil material it carries (index into the case's materials; 0, the first, by default).
  int inflow_material = 0;
  // Inlet: its velocity at a factor of 1, and the factor by time, pairs (t, factor) of non-decreasing
  // t, linear between them, the first factor before the first and the last after the last (a jump:
  // two pairs of one time, the later one holding from that time on). None: a factor of 1 throughout.
  // `velocity` holds inflow_velocity times the factor at the time the flow is solved for.
  std::array<double, 3> inflow_velocity{0.0, 0.0, 0.0};
  std::vector<std::array<double, 2>> inflow_schedule;
  // Inlet: its opening, [low, high] along each axis across the side (the entry along the side's normal
  // is not read); outside it the side is a wall at rest. Infinite: the whole side is open.
  std::array<std::array<double, 2>, 3> inflow_span{{{-std::numeric_limits<double>::infinity(),
                                                     std::numeric_limits<double>::infinity()},
                                                    {-std::numeric_limits<double>::infinity(),
                                                     std::numeric_limits<double>::infinity()},
                                                    {-std::numeric_limits<double>::infinity(),
                                                     std::numeric_limits<double>::infinity()}}};
  // Density of what lies beyond an open bottom (the mixture at inflow_soil_fraction; the fluid of a
  // single-phase case), whose hydrostatic head below the top the bottom's pressure is. 0: unset.
  double outside_density = 0.0;
};

using BoundarySet = std::array<BoundaryCondition, 6>;  // indexed by Side; front and back for 3D meshes

// The condition on an obstacle's faces (mesh/obstacles.hpp): a static no-slip wall.
inline constexpr BoundaryCondition obstacle_wall{};

inline const BoundaryCondition& boundary(const BoundarySet& b, Side s) { return b[static_cast<int>(s)]; }

// A side that holds every velocity component at its own (no-slip, Dirichlet): a wall or an inlet.
inline bool holds_velocity(const BoundaryCondition& bc) {
  return bc.kind == BoundaryKind::wall || bc.kind == BoundaryKind::inlet;
}


inline bool has_inlet(const BoundarySet& b) {
  return std::any_of(b.begin(), b.end(), [](const BoundaryCondition& bc) { return bc.kind == BoundaryKind::inlet; });
}

// An inlet that lets soil in (when its velocity's factor is not zero).
inline bool carries_soil(const BoundaryCondition& bc) {
  return bc.kind == BoundaryKind::inlet && bc.inflow_soil_fraction > 0.0;
}

// An inlet open over part of its side only (BoundaryCondition::inflow_span).
inline bool opens_in_part(const BoundaryCondition& bc) {
  if (bc.kind != BoundaryKind::inlet) return false;
  for (const auto& span : bc.inflow_span)
    if (std::isfinite(span[0]) || std::isfinite(span[1])) return true;
  return false;
}

// The share of the face that the side's cell (or ghost) i, j, k has on the side which lies in a span
// ([low, high] along each axis across the side), or in an inlet's opening: by length across the side,
// by r dr along an axisymmetric mesh's radius (so that the share times the face's area is the open
// area). 1 on any other side and on an inlet open over the whole side. A ghost beyond an edge of the
// side takes the share of the side's cell it lies beside (across a periodic join, the cell it stands
// for), so that an opening to the end of the side is open there whatever end it is given.
inline double span_share(const std::array<std::array<double, 2>, 3>& span, const Grid& grid, Side side, int i, int j,
                         int k) {
  const int n[3] = {grid.nx(), grid.ny(), grid.nz()};
  int at[3] = {i, j, k};
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == 0 && grid.periodic_x()) at[axis] = (at[axis] % n[axis] + n[axis]) % n[axis];
    at[axis] = std::clamp(at[axis], 0, n[axis] - 1);
  }
  double share = 1.0;
  for (int axis = 0; axis < grid.dimension(); ++axis) {
    if (axis == normal_axis(side)) continue;
    const double low = grid.centre(axis, at[axis]) - 0.5 * grid.width(axis, at[axis]);
    const double high = low + grid.width(axis, at[axis]);
    const double from = std::max(low, span[axis][0]), to = std::min(high, span[axis][1]);
    if (!(to > from)) return 0.0;
    share *= axis == 0 && grid.axisymmetric() ? (to * to - from * from) / (high * high - low * low)
                                              : (to - from) / (high - low);
  }
  return share;
}
inline double open_share(const BoundaryCondition& bc, const Grid& grid, Side side, int i, int j, int k) {
  return opens_in_part(bc) ? span_share(bc.inflow_span, grid, side, i, j, k) : 1.0;
}

// The velocity a side holds at the face of its cell (or ghost) i, j, k: a wall's, or an inlet's over
// the face's open share (its mean over the face; a wall at rest outside the opening).
inline std::array<double, 3> held_velocity(const BoundaryCondition& bc, const Grid& grid, Side side, int i, int j,
                                           int k) {
  if (!opens_in_part(bc)) return bc.velocity;
  const double share = open_share(bc, grid, side, i, j, k);
  return {share * bc.velocity[0], share * bc.velocity[1], share * bc.velocity[2]};
}

// Whether the face of the side's cell (or ghost) i, j, k lets an inlet's inflow in: an inlet's face
// with some of it open.
inline bool lets_in(const BoundaryCondition& bc, const Grid& grid, Side side, int i, int j, int k) {
  return bc.kind == BoundaryKind::inlet && open_share(bc, grid, side, i, j, k) > 0.0;
}

// The factor on an inlet's velocity at time t (BoundaryCondition::inflow_schedule).
inline double inflow_factor(const std::vector<std::array<double, 2>>& schedule, double t) {
  if (schedule.empty()) return 1.0;
  size_t k = schedule.size();  // after the loop, schedule[k - 1] is the last pair at or before t
  while (k > 0 && schedule[k - 1][0] > t) --k;
  if (k == 0) return schedule.front()[1];  // before the first time
  const auto& a = schedule[k - 1];
  if (k == schedule.size()) return a[1];  // after the last
  const auto& b = schedule[k];  // b's time is past t, so past a's: no division by zero
  return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
}

// The first time of an inlet's schedule after t (steps land on it, so that a step of the schedule is
// met exactly); infinity where there is none.
inline double next_inflow_time(const BoundarySet& b, double t) {
  double next = std::numeric_limits<double>::infinity();
  for (const auto& bc : b)
    if (bc.kind == BoundaryKind::inlet)
      for (const auto& point : bc.inflow_schedule)
        if (point[0] > t * (1 + 1e-12) + 1e-300) next = std::min(next, point[0]);
  return next;
}

// The time at which a step ending at t_end, of size dt, takes its inlets' schedules: the middle of the
// step after it, taken to be as long (or to end at the schedule's next time), over which the faces its
// solve leaves carry the inflow. Exact for a factor that is constant between the schedule's times,
// second order in the step across a ramp.
inline double inflow_time_after(const BoundarySet& b, double t_end, double dt) {
  return 0.5 * (t_end + std::min(t_end + dt, next_inflow_time(b, t_end)));
}

// The velocity along the side's normal through the face of its cell i, j, k where the side fixes it:
// an inlet's inflow (over the face's open share), zero through a wall or a slip side. Atmosphere sides
// have none of their own (their flux is solved for).
inline double imposed_normal_velocity(const BoundaryCondition& bc, const Grid& grid, Side side, int i, int j, int k) {
  if (bc.kind != BoundaryKind::inlet) return 0.0;
  return open_share(bc, grid, side, i, j, k) * bc.velocity[normal_axis(side)];
}

// Inflow soil fraction of an inlet's face whose extent along y is [y_low, y_high], the domain's bottom
// at y_bottom: the share of the face's opening below the inlet's soil depth, times its soil fraction.
inline double inlet_face_soil_fraction(const BoundaryCondition& bc, double y_low, double y_high, double y_bottom) {
  y_low = std::max(y_low, bc.inflow_span[1][0]);  // the open part of the face (all of it without a span)
  y_high = std::min(y_high, bc.inflow_span[1][1]);
  if (!(y_high > y_low)) return 0.0;
  const double top = y_bottom + bc.inflow_soil_depth;
  const double below = std::clamp((top - y_low) / (y_high - y_low), 0.0, 1.0);
  return bc.inflow_soil_fraction * below;
}

// The pressure of the surroundings, Pa: the p0 of the north side if it is open, else the lowest p0
// of the open sides; 0 in a closed domain, whose pressure is held at zero on its top
// (FlowSolver). A granular phase's yield stress takes the pressure above it: dry soil under air at
// p0 is no stronger than at 0.
inline double ambient_pressure(const BoundarySet& b) {
  const auto& north = b[static_cast<int>(Side::north)];
  if (north.kind == BoundaryKind::atmosphere) return north.pressure;
  double lowest = 0.0;
  bool open = false;
  for (const auto& bc : b)
    if (bc.kind == BoundaryKind::atmosphere) {
      lowest = open ? std::min(lowest, bc.pressure) : bc.pressure;
      open = true;
    }
  return lowest;
}


// Pressure at an atmosphere face: p0 plus the hydrostatic head below the top of the domain
// (hydrostatic_head, Pa), minus rho v_n^2 / 2 where fluid flows in (total pressure) unless the
// boundary is static; rho is the density of the adjacent cell, outward_velocity the face's, and
// normal2 the square of the adjacent cell's velocity normal to the side. The head of the normal
// velocity only: with the whole speed's, air that a flowing layer drags along the top lost
// rho u^2 / 2 of pressure where it happened to flow in and not where it flowed out, which drove a
// circulation in and out through the top (docs/method.md, the boundary conditions' table).
double atmosphere_pressure(const BoundaryCondition& bc, double hydrostatic_head, double rho, double outward_velocity,
                           double normal2);

}  // namespace granflow

#pragma once
// Boundary conditions of the flow, one per side of the box.
#include <algorithm>
#include <array>
#include <optional>

#include "mesh/grid.hpp"
#include "models/rheology/wall_friction.hpp"

namespace granflow {

enum class BoundaryKind {
  wall,        // no-slip; a non-zero wall velocity makes it a moving (sliding) wall
  slip,        // impermeable, free of shear
  atmosphere,  // fixed total pressure: outflow at the static pressure, inflow at p0 - rho|u|^2/2
  periodic,    // west and east joined (GridSpec::periodic_x): no boundary there
};

struct BoundaryCondition {
  BoundaryKind kind = BoundaryKind::wall;
  std::array<double, 3> wall_velocity{0.0, 0.0, 0.0};  // tangential part is used; normal part must be zero
  // A wall of its own Coulomb friction against the soil (models/rheology/wall_friction.hpp); without
  // it the soil's own strength is what holds it at the wall.
  std::optional<rheology::WallFriction> friction;
  double pressure = 0.0;                          // atmosphere: total pressure p0
  bool total_pressure = true;                     // false: p0 is the static pressure also for inflow
  // Soil fraction carried in by inflow through an atmosphere boundary.
  double inflow_soil_fraction = 0.0;
  // Density of what lies beyond an open bottom (the mixture at inflow_soil_fraction; the fluid of a
  // single-phase case), whose hydrostatic head below the top the bottom's pressure is. 0: unset.
  double outside_density = 0.0;
};

using BoundarySet = std::array<BoundaryCondition, 6>;  // indexed by Side; front and back for 3D meshes

// The condition on an obstacle's faces (mesh/obstacles.hpp): a static no-slip wall.
inline constexpr BoundaryCondition obstacle_wall{};

inline const BoundaryCondition& boundary(const BoundarySet& b, Side s) { return b[static_cast<int>(s)]; }

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

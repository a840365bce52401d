#pragma once
// Point samples of a gathered cell field, for line output and comparisons with tabulated data.
//
// Between cell centres the sample is bilinear (trilinear on a mesh of layers). Between the last centre
// and a side of the domain it interpolates towards the value on the side, which each side's rule
// gives: the boundary condition (a wall's velocity), the next cell's value (a zero gradient), or the
// last two cells' line continued (a pressure against a wall, which carries the hydrostatic gradient). So a profile
// sampled up to a wall ends on the wall's value instead of stopping half a cell short of it.
#include <array>
#include <vector>

#include "mesh/grid.hpp"
#include "solver/boundary.hpp"

namespace granflow {

struct SideRule {
  enum class Kind { value, zero_gradient, linear };
  Kind kind = Kind::zero_gradient;
  double value = 0.0;  // the value on the side, for Kind::value
  // The value holds over this span of the side ([low, high] along each axis across it), and is zero
  // outside: an inlet open in part (BoundaryCondition::inflow_span). A face cut by it takes its share.
  std::array<std::array<double, 2>, 3> span = BoundaryCondition{}.inflow_span;
};
using SideRules = std::array<SideRule, 6>;  // indexed by Side (a planar mesh reads the first four)

// The rules for velocity component `axis` (0 = x, 1 = y, 2 = z) on the sides of a mesh of `dimension`:
// a wall's velocity on a wall (normal part zero), an inlet's over its opening, zero normal velocity and a
// free tangential one on a slip side, a zero gradient at an atmosphere.
SideRules velocity_side_rules(const BoundarySet& boundaries, int axis, int dimension);
// The rules for the pressure: the last two cells' line continued on every side.
SideRules pressure_side_rules();

// Sample of a field gathered on rank 0 (index (k * ny + j) * nx + i) at (x, y, z) inside the domain
// (bounds included); points outside are taken at the nearest point of the domain. A planar mesh
// ignores z. Near an edge or a corner of the domain the rules apply along x, then y, then z: a
// corner's value is the later side's rule applied to the values the earlier sides give. Where the
// west and east sides are periodic, there is no side: the join between the two end columns holds
// their mean, whatever the rules say (every field is periodic across it).
double sample_field(const Grid& grid, const std::vector<double>& values, const SideRules& sides, double x, double y,
                    double z = 0.0);

// An obstacle's walls for sampling: each blocked cell (blocked[k] > 0.5, gathered like values) beside
// an open cell takes the value that puts the wall's rule on the face between them, so that a sample
// within half a cell of an obstacle runs to the wall's value as one near a side of the domain does:
// 2 v - open for a value v (a static wall's velocity, 0), the open cell's for a zero gradient, and for
// the pressure the line of the open cell and the one beyond it continued. The open neighbour is the
// nearest wall's, along y, then x, then z where the cell has open neighbours along several axes (an
// obstacle's edge or corner). A blocked cell with no open neighbour but one diagonal to it across an
// edge (in a corner two walls make) takes that cell's value mirrored across both walls; on a mesh of
// layers, one with only an open cell diagonal across a corner (three walls), mirrored across all three.
// Where the west and east sides are periodic, a cell's neighbours along x run on through the join.
void fill_obstacle_walls(const Grid& grid, const std::vector<double>& blocked, const SideRule& wall,
                         std::vector<double>& values);

}  // namespace granflow

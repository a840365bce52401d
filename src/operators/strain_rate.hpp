#pragma once
// Discrete strain-rate tensor D = (grad v + grad v^T) / 2 of the cell-centred velocity, at a cell
// centre or on a face. The velocity arrays are ghosted, ghosts encoding the boundaries: [j][i] of the
// two components of a planar or axisymmetric mesh, or [k][j][i] of the three of a mesh of layers.
#include <array>

#include "mesh/grid.hpp"
#include "models/rheology/invariants.hpp"

namespace granflow {

// At the centre of cell (i, j), from central differences.
rheology::StrainRate cell_strain_rate(const Grid& g, const double* const* u, const double* const* v, int i, int j);

// On the face between cell (i, j) and its neighbour at +1 along axis (either may be a ghost): the
// derivatives across the face compact, those along it the mean of the two cells' central ones.
rheology::StrainRate face_strain_rate(const Grid& g, const double* const* u, const double* const* v, int axis, int i,
                                      int j);

// The three velocity components' ghosted arrays [k][j][i] of a mesh of several layers.
using VelocityArrays3 = std::array<const double* const* const*, 3>;

// At the centre of cell (i, j, k) of a 3D mesh, from central differences of all three components.
rheology::StrainRate cell_strain_rate(const Grid& g, const VelocityArrays3& v, int i, int j, int k);

// On the face between cell (i, j, k) and its neighbour at +1 along axis, in 3D: as face_strain_rate
// above, the derivatives across the face compact, those along it the mean of the two cells' central
// ones.
rheology::StrainRate face_strain_rate(const Grid& g, const VelocityArrays3& v, int axis, int i, int j, int k);

// Derivative at a wall, along the distance from it, of a quantity worth `wall` there and f1, f2 at
// the first two cell centres (s1 and s2 from the wall): quadratic through the three. The momentum
// flux and the wall face's strain rate both take it, so that a plastic stress stays on its yield
// surface.
inline double quadratic_wall_derivative(double f1, double f2, double wall, double s1, double s2) {
  return ((f1 - wall) * s2 / s1 - (f2 - wall) * s1 / s2) / (s2 - s1);
}

// On the wall face of cell (i, j) at `sign` (-1 low, +1 high) along `axis`: as face_strain_rate, but
// with the derivatives across the wall quadratic through the wall and the first two cell centres, as
// the momentum flux takes them under numerics.wall_gradient = "quadratic". `wall_velocity` is the
// wall's (its normal component zero) or an inlet's; `no_shear` (a slip wall) keeps the tangential
// component's derivative at zero.
rheology::StrainRate quadratic_wall_strain_rate(const Grid& g, const double* const* u, const double* const* v, int axis,
                                                int i, int j, int sign, std::array<double, 2> wall_velocity,
                                                bool no_shear);

// The same on the wall face of cell (i, j, k) of a mesh of layers: the three components' derivatives
// across the wall quadratic (both tangential ones zero on a slip wall), those along it the wall face's.
rheology::StrainRate quadratic_wall_strain_rate(const Grid& g, const VelocityArrays3& v, int axis, int i, int j, int k,
                                                int sign, std::array<double, 3> wall_velocity, bool no_shear);

}  // namespace granflow

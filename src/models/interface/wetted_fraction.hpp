// How much of a cell's side its soil touches, from the PLIC reconstruction.
#pragma once

namespace granflow::interface {

// Length fraction of side (axis, sign) of cell (i, j) covered by the cell's soil: the side normal to
// `axis` (0 = x, 1 = y) on the low (sign = -1) or high (+1) end. The interface is the cell's PLIC
// line (MYC normal from the 3 x 3 block, read from a ghosted [j][i] array with global indices, as in
// vof_sweep). A layer of soil lying on the side covers all of it whatever its c; an interface at
// right angles to the side covers the fraction c. Pure cells give 0 or 1; a block too flat to
// orient (a spread of c below 1e-8) gives c.
// Why: the soil fraction of a wall face is what decides whether the wall rubs on soil or on air. The
// cell's own c says a film one tenth of a cell thick on the floor is one tenth soil, but all of the
// floor under it is soil.
// With `radius_centre` (an axisymmetric mesh's centre radii, indexed like dx) the line holds c of the
// radius-weighted area, and a side normal to y counts its points by their radius (plic_geometry.hpp).
double wetted_side_fraction(const double* const* c, const double* dx, const double* dy, int i, int j,
                            int axis, int sign, const double* radius_centre = nullptr);

// The same on a mesh of layers: the area fraction of face (axis, sign) of cell (i, j, k) (axis 2 = z)
// under the cell's PLIC plane (the mixed Youngs-centred normal of its 3 x 3 x 3 block, read from a
// ghosted [k][j][i] array).
double wetted_side_fraction(const double* const* const* c, const double* dx, const double* dy, const double* dz,
                            int i, int j, int k, int axis, int sign);

}  // namespace granflow::interface

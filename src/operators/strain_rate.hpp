#pragma once
// Discrete strain-rate tensor D = (grad v + grad v^T) / 2 of the cell-centred velocity, at a cell
// centre or on a face. The velocity arrays are ghosted ([j][i], ghosts encoding the boundaries).
#include "mesh/grid.hpp"
#include "models/rheology/invariants.hpp"

namespace granflow {

// At the centre of cell (i, j), from central differences.
rheology::StrainRate cell_strain_rate(const Grid& g, const double* const* u, const double* const* v, int i, int j);

// On the face between cell (i, j) and its neighbour at +1 along axis (either may be a ghost): the
// derivatives across the face compact, those along it the mean of the two cells' central ones.
rheology::StrainRate face_strain_rate(const Grid& g, const double* const* u, const double* const* v, int axis, int i,
                                      int j);

}  // namespace granflow

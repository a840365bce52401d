#pragma once
// Ghosts for a cell field with no boundary condition of its own (a density, a viscosity, a pressure
// before its boundary faces are set, a displacement): each ghost copies the nearest cell at the
// domain's sides, and blocked cells mirror the open cells next to them.
#include "mesh/field.hpp"
#include "mesh/grid.hpp"

namespace granflow {

// Scatters f's owned values to its local vector, then fills the ghosts there (blocked: the obstacle
// mask, or null without obstacles).
void fill_copied_ghosts(const Grid& grid, const Field* blocked, Field& f);

}  // namespace granflow

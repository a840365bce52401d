#pragma once
// The velocity's ghosts beyond the domain's sides, which encode each side's boundary condition so that
// stencils near a side need no special cases: a wall's ghost mirrors the cell so that the face takes the
// wall's velocity, a slip wall's mirrors the normal component with its sign turned and the tangential
// ones as they are, an atmosphere's repeats the first cell (zero gradient). A periodic side has none
// of its own: the exchange filled them.
#include <span>

#include "mesh/grid.hpp"
#include "solver/boundary.hpp"

namespace granflow {

// components[c]: the local (ghosted) array [k][j][i] of velocity component c, one per axis of the
// mesh. The sides' ghosts this rank holds are filled in the passes of mesh/side_ghosts.hpp: an edge's
// or a corner's ghost takes the later side's rule applied to the earlier side's ghosts.
void fill_velocity_side_ghosts(const Grid& grid, const BoundarySet& boundaries, std::span<double*** const> components);

}  // namespace granflow

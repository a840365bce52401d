#pragma once
// Obstacles and terrain as blocked cells (SPEC 3): a 0/1 mask over the cells, 1 where the cell is
// solid. A face between an open and a blocked cell is a no-slip wall, treated as the domain's walls
// are; a blocked cell holds no soil, no flow and no unknowns of the coupled solve.
//
// Stencils that reach across a wall read the ghost values behind it (FlowSolver, SoilPhase). The
// domain's walls get theirs from the boundary conditions; an obstacle's blocked cells get them from
// mirror_into_blocked, in the local (ghosted) arrays only: the global vectors keep zero there.
#include <optional>
#include <span>
#include <vector>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "models/interface/initial_shapes.hpp"
#include "models/interface/initial_shapes_3d.hpp"

namespace granflow {

// Whether cell (i, j, k) is blocked (k = 0 on a planar mesh), from a local mask array (null: no
// obstacles). Cells outside the domain are not: their ghosts hold 0.
inline bool is_blocked(VolumeView mask, int i, int j, int k) { return mask && mask[k][j][i] > 0.5; }

// Read access to the local mask of blocked cells, or none (data() null) without obstacles.
class BlockedView {
 public:
  BlockedView(const Grid& g, const Field* mask) {
    if (mask) data_ = array_.emplace(g.field_dm(), mask->local()).volume();
  }
  VolumeView data() const { return data_; }

 private:
  std::optional<ConstFieldArray> array_;
  VolumeView data_ = nullptr;
};

// Marks the cells whose centre lies in any of the shapes (1, else 0), ghosts included; returns the
// number of blocked cells over all ranks. Collective. A planar mesh takes planar shapes, a mesh of
// layers solids, and leaves open the cells `kept_open` lists (global indices (k * ny + j) * nx + i,
// ascending, the same on every rank: ridges one cell wide lowered, mesh/thin_ridges.hpp).
long mark_blocked_cells(const Grid& g, const interface::ShapeUnion& shapes, Field& mask);
long mark_blocked_cells(const Grid& g, const interface::ShapeUnion3& solids, Field& mask,
                        std::span<const long> kept_open = {});

// Marks each cell with one plus the index of the last shape that holds its centre, 0 where none does,
// ghosts included: which obstacle a blocked cell belongs to (the last listed where they overlap).
void mark_obstacle_index(const Grid& g, const interface::ShapeUnion& shapes, Field& index);
void mark_obstacle_index(const Grid& g, const interface::ShapeUnion3& solids, Field& index);

// Sets the blocked cells of f's global vector to zero (its local vector is left as it is): after a
// copy from the local values, e.g. a restored snapshot or a checkpoint, which hold the mirrors.
void zero_blocked_cells(const Grid& g, const Field* mask, Field& f);

// Fills the blocked cells of the local array `a` as ghosts of the walls they form: a blocked cell k
// cells behind its nearest wall takes sign times the open cell k - 1 cells in front of it (sign -1:
// a no-slip velocity, +1: a scalar of zero normal gradient), as the domain's ghosts do, for k up to
// the ghost width. Its nearest wall along any axis; where walls along two axes are as near (an
// obstacle's edge or corner), the one along the later axis (z before y before x), as the domain's
// edge and corner ghosts are filled (mesh/side_ghosts.hpp). Open cells are those inside the domain;
// cells without an open cell within reach are left as they are. A blocked cell with walls on both
// sides along one axis (an obstacle one cell thick) cannot mirror both; lay_out_obstacles refuses
// such cells. mask: the blocked cells (null: none). Which cell mirrors which is found once for a mask
// laid out by mark_blocked_cells, which must then only be read; a mask filled otherwise, at each call.
void mirror_into_blocked(const Grid& g, const Field* mask, double*** a, double sign);

}  // namespace granflow

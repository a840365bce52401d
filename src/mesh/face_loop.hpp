#pragma once
// Visits every face of the owned cells of a face field, in the layout of FlowSolver's face fields:
// [j][i] of axis 0 is the face between cells (i, j) and (i+1, j), [j][-1] and [j][nx-1] the west and
// east boundary faces; axis 1 likewise in j. Faces shared with the ghost column or row on the low
// side are visited too, so that a stencil over the owned cells needs no exchange. With periodic x the
// end faces are interior faces between a cell and a ghost of the other end.
#include <algorithm>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "mesh/obstacles.hpp"

namespace granflow {

// interior(axis, i, j): value of the face between (i, j) and its neighbour at +1 along axis;
// boundary(axis, i, j, sign): value of the boundary face of cell (i, j) on its sign side. With a
// mask of blocked cells (mesh/obstacles.hpp), a face between an open and a blocked cell is the open
// cell's boundary face too (an obstacle's wall), and a face between two blocked cells is 0.
template <class Interior, class Boundary>
void fill_owned_faces(const Grid& g, Field& x_faces, Field& y_faces, Interior interior, Boundary boundary,
                      const double* const* blocked = nullptr) {
  const auto& b = g.owned();
  const int nx = g.nx(), ny = g.ny();
  FieldArray fx = local_array(g, x_faces), fy = local_array(g, y_faces);
  // The face between (i, j) and (i + di, j + dj), both in the domain.
  auto inner = [&](int axis, int i, int j) {
    const int in = i + (axis == 0), jn = j + (axis == 1);
    const bool low = is_blocked(blocked, i, j), high = is_blocked(blocked, in, jn);
    if (low && high) return 0.0;
    if (low) return boundary(axis, in, jn, -1);
    if (high) return boundary(axis, i, j, 1);
    return interior(axis, i, j);
  };
  const bool periodic = g.periodic_x();  // the x faces at the ends join a cell to a ghost of the other end
  for (int j = b.ys; j < b.ye(); ++j) {
    if (b.xs == 0 && !periodic) fx[j][-1] = boundary(0, 0, j, -1);
    for (int i = periodic ? b.xs - 1 : std::max(b.xs - 1, 0); i < b.xe(); ++i)
      fx[j][i] = i + 1 == nx && !periodic ? boundary(0, i, j, 1) : inner(0, i, j);
  }
  for (int i = b.xs; i < b.xe(); ++i) {
    if (b.ys == 0) fy[-1][i] = boundary(1, i, 0, -1);
    for (int j = std::max(b.ys - 1, 0); j < b.ye(); ++j)
      fy[j][i] = j + 1 == ny ? boundary(1, i, j, 1) : inner(1, i, j);
  }
}

}  // namespace granflow

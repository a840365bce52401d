#pragma once
// Visits every face of the owned cells of a face field, in the layout of FlowSolver's face fields:
// [j][i] of axis 0 is the face between cells (i, j) and (i+1, j), [j][-1] and [j][nx-1] the west and
// east boundary faces; axis 1 likewise in j. Faces shared with the ghost column or row on the low
// side are visited too, so that a stencil over the owned cells needs no exchange. With periodic x the
// end faces are interior faces between a cell and a ghost of the other end.
#include <algorithm>
#include <array>
#include <cassert>

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
                      VolumeView blocked = nullptr) {
  const auto& b = g.owned();
  const int nx = g.nx(), ny = g.ny();
  FieldArray fx = local_array(g, x_faces), fy = local_array(g, y_faces);
  // The face between (i, j) and (i + di, j + dj), both in the domain.
  auto inner = [&](int axis, int i, int j) {
    const int in = i + (axis == 0), jn = j + (axis == 1);
    const bool low = is_blocked(blocked, i, j, 0), high = is_blocked(blocked, in, jn, 0);
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

// On a mesh of several layers: faces[a] holds the faces normal to axis a, [k][j][i] the face between
// cell (i, j, k) and its neighbour at +1 along a, index -1 along a the low boundary face; each owned
// cell's six faces, those on the low side of the block included. interior(axis, i, j, k) and
// boundary(axis, i, j, k, sign) as above, obstacles' walls too. With periodic x the end faces along x
// are interior faces between a cell and a ghost of the other end, as in 2D.
template <class Interior, class Boundary>
void fill_owned_faces_3d(const Grid& g, const std::array<Field*, 3>& faces, Interior interior, Boundary boundary,
                         VolumeView blocked = nullptr) {
  assert(g.dimension() == 3);
  const auto& b = g.owned();
  const int n[3] = {g.nx(), g.ny(), g.nz()};
  const int start[3] = {b.xs, b.ys, b.zs}, end[3] = {b.xe(), b.ye(), b.ze()};
  for (int axis = 0; axis < 3; ++axis) {
    FieldArray f = local_array(g, *faces[axis]);
    double*** a = f.volume();
    int lo[3] = {start[0], start[1], start[2]};
    lo[axis] = start[axis] - 1;  // the faces on the block's low side: the boundary's, or a ghost's high faces
    for (int k = lo[2]; k < end[2]; ++k)
      for (int j = lo[1]; j < end[1]; ++j)
        for (int i = lo[0]; i < end[0]; ++i) {
          const int along = axis == 0 ? i : (axis == 1 ? j : k);
          const int in = i + (axis == 0), jn = j + (axis == 1), kn = k + (axis == 2);
          const bool joined = axis == 0 && g.periodic_x();
          if (along < 0 && !joined) {
            a[k][j][i] = boundary(axis, in, jn, kn, -1);
            continue;
          }
          if (along + 1 == n[axis] && !joined) {
            a[k][j][i] = boundary(axis, i, j, k, 1);
            continue;
          }
          const bool low = is_blocked(blocked, i, j, k), high = is_blocked(blocked, in, jn, kn);
          if (low && high) a[k][j][i] = 0.0;
          else if (low) a[k][j][i] = boundary(axis, in, jn, kn, -1);
          else if (high) a[k][j][i] = boundary(axis, i, j, k, 1);
          else a[k][j][i] = interior(axis, i, j, k);
        }
  }
}

// Either of the two above, by the mesh's dimension: interior(axis, i, j, k) and boundary(axis, i, j, k,
// sign) with k = 0 on a planar mesh, whose faces[2] is not read.
template <class Interior, class Boundary>
void fill_owned_faces_any(const Grid& g, const std::array<Field*, 3>& faces, Interior interior, Boundary boundary,
                          VolumeView blocked = nullptr) {
  if (g.dimension() == 3) {
    fill_owned_faces_3d(g, faces, interior, boundary, blocked);
    return;
  }
  fill_owned_faces(
      g, *faces[0], *faces[1], [&](int axis, int i, int j) { return interior(axis, i, j, 0); },
      [&](int axis, int i, int j, int sign) { return boundary(axis, i, j, 0, sign); }, blocked);
}

}  // namespace granflow

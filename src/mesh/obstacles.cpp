#include "mesh/obstacles.hpp"

#include <mpi.h>

namespace granflow {

namespace {
// The owned values to the local vector, and 0 in the ghosts beyond the domain's boundaries.
void scatter_with_no_obstacle_outside(const Grid& g, Field& f) {
  f.scatter_to_local();
  FieldArray m = local_array(g, f);
  const auto& b = g.owned();
  const int gw = Grid::ghost_width;
  for (int j = b.ys - gw; j < b.ye() + gw; ++j)
    for (int i = b.xs - gw; i < b.xe() + gw; ++i)
      if (g.outside(i, j)) m[j][i] = 0.0;  // beyond a periodic side: the other end's cells
}
}  // namespace

long mark_blocked_cells(const Grid& g, const interface::ShapeUnion& shapes, Field& mask) {
  long count = 0;
  {
    FieldArray m(g.field_dm(), mask.global());
    const auto& b = g.owned();
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        m[j][i] = shapes.contains(g.xc(i), g.yc(j)) ? 1.0 : 0.0;
        count += m[j][i] > 0.5;
      }
  }
  scatter_with_no_obstacle_outside(g, mask);  // ghosts outside the domain are not blocked
  long total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_LONG, MPI_SUM, g.comm());
  return total;
}

void mark_obstacle_index(const Grid& g, const interface::ShapeUnion& shapes, Field& index) {
  {
    FieldArray m(g.field_dm(), index.global());
    const auto& b = g.owned();
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        m[j][i] = 0.0;
        for (size_t k = 0; k < shapes.size(); ++k)
          if (shapes.shape_contains(k, g.xc(i), g.yc(j))) m[j][i] = double(k + 1);
      }
  }
  scatter_with_no_obstacle_outside(g, index);  // ghosts outside the domain belong to no obstacle
}

void zero_blocked_cells(const Grid& g, const Field* mask, Field& f) {
  if (!mask) return;
  const BlockedView m(g, mask);
  FieldArray a(g.field_dm(), f.global());
  const auto& b = g.owned();
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i)
      if (is_blocked(m.data(), i, j)) a[j][i] = 0.0;
}

void mirror_into_blocked(const Grid& g, const double* const* mask, double** a, double sign) {
  if (!mask) return;
  const auto& b = g.owned();
  const int gw = Grid::ghost_width;
  const int i_lo = b.xs - gw, i_hi = b.xe() + gw, j_lo = b.ys - gw, j_hi = b.ye() + gw;  // the local array
  auto open = [&](int i, int j) {
    return i >= i_lo && i < i_hi && j >= j_lo && j < j_hi && !g.outside(i, j) && mask[j][i] <= 0.5;
  };
  // The mirror of blocked cell (i, j) across the wall `depth` cells away along (di, dj), if that is
  // where the nearest open cell lies: the open cell depth - 1 beyond the wall (or the first one, if
  // the open region there is thinner).
  auto mirror = [&](int i, int j, int di, int dj, int depth, double& value) {
    for (int k = 1; k < depth; ++k) {  // the cells between must be blocked (and in the local array)
      const int ib = i + k * di, jb = j + k * dj;
      if (ib < i_lo || ib >= i_hi || jb < j_lo || jb >= j_hi || !is_blocked(mask, ib, jb)) return false;
    }
    const int iw = i + depth * di, jw = j + depth * dj;  // the first cell beyond the wall
    if (!open(iw, jw)) return false;
    const int im = iw + (depth - 1) * di, jm = jw + (depth - 1) * dj;
    value = sign * (open(im, jm) ? a[jm][im] : a[jw][iw]);
    return true;
  };
  // The nearest wall along an axis, as its depth (0: none within reach); on a tie (a wall on either
  // side) the high side's.
  auto nearest = [&](int i, int j, int di, int dj, double& value) {
    for (int depth = 1; depth <= gw; ++depth)
      if (mirror(i, j, di, dj, depth, value) || mirror(i, j, -di, -dj, depth, value)) return depth;
    return 0;
  };
  // Each blocked cell mirrors across its nearest wall: it is the ghost of the open cell that wall
  // faces. A cell as near to a wall along x as along y (an obstacle's corner) takes y's, as the
  // domain's corner ghosts do; a cell nearer to a wall along x keeps x's, as the domain's ghosts
  // behind its west and east sides do.
  for (int j = j_lo; j < j_hi; ++j)
    for (int i = i_lo; i < i_hi; ++i) {
      if (!is_blocked(mask, i, j)) continue;
      double along_x = 0.0, along_y = 0.0;
      const int depth_x = nearest(i, j, 1, 0, along_x), depth_y = nearest(i, j, 0, 1, along_y);
      if (depth_y > 0 && (depth_x == 0 || depth_y <= depth_x)) a[j][i] = along_y;
      else if (depth_x > 0) a[j][i] = along_x;
    }
}

}  // namespace granflow

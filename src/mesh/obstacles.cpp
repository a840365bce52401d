#include "mesh/obstacles.hpp"

#include <mpi.h>

namespace granflow {

namespace {
// The local array's extent: the owned block and its ghosts, one layer (k = 0) on a planar mesh.
struct LocalExtent {
  int lo[3], hi[3];
  explicit LocalExtent(const Grid& g) {
    const auto& b = g.owned();
    const int gw = Grid::ghost_width;
    const bool layers = g.dimension() == 3;
    lo[0] = b.xs - gw, hi[0] = b.xe() + gw;
    lo[1] = b.ys - gw, hi[1] = b.ye() + gw;
    lo[2] = layers ? b.zs - gw : 0, hi[2] = layers ? b.ze() + gw : 1;
  }
  bool holds(int i, int j, int k) const {
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
  }
};

// The owned values to the local vector, and 0 in the ghosts beyond the domain's boundaries.
void scatter_with_no_obstacle_outside(const Grid& g, Field& f) {
  f.scatter_to_local();
  FieldArray m = local_array(g, f);
  const LocalExtent e(g);
  for (int k = e.lo[2]; k < e.hi[2]; ++k)
    for (int j = e.lo[1]; j < e.hi[1]; ++j)
      for (int i = e.lo[0]; i < e.hi[0]; ++i)
        if (g.outside(i, j, k)) m.volume()[k][j][i] = 0.0;  // beyond a periodic side: the other end's cells
}

// Marks the owned cells whose centre `inside(i, j, k)` holds, then the ghosts; the count over all ranks.
template <class Inside>
long mark_cells(const Grid& g, Inside inside, Field& mask) {
  long count = 0;
  {
    FieldArray m(g.field_dm(), mask.global());
    const auto& b = g.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          m.volume()[k][j][i] = inside(i, j, k) ? 1.0 : 0.0;
          count += m.volume()[k][j][i] > 0.5;
        }
  }
  scatter_with_no_obstacle_outside(g, mask);  // ghosts outside the domain are not blocked
  long total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_LONG, MPI_SUM, g.comm());
  return total;
}
}  // namespace

long mark_blocked_cells(const Grid& g, const interface::ShapeUnion& shapes, Field& mask) {
  return mark_cells(g, [&](int i, int j, int) { return shapes.contains(g.xc(i), g.yc(j)); }, mask);
}

long mark_blocked_cells(const Grid& g, const interface::ShapeUnion3& solids, Field& mask) {
  return mark_cells(g, [&](int i, int j, int k) { return solids.contains(g.xc(i), g.yc(j), g.zc(k)); }, mask);
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
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        if (is_blocked(m.data(), i, j, k)) a.volume()[k][j][i] = 0.0;
}

void mirror_into_blocked(const Grid& g, VolumeView mask, double*** a, double sign) {
  if (!mask) return;
  const LocalExtent e(g);
  const int gw = Grid::ghost_width, axes = g.dimension() == 3 ? 3 : 2;
  auto open = [&](int i, int j, int k) { return e.holds(i, j, k) && !g.outside(i, j, k) && mask[k][j][i] <= 0.5; };
  // The mirror of blocked cell (i, j, k) across the wall `depth` cells away along d, if that is where
  // the nearest open cell lies: the open cell depth - 1 beyond the wall (or the first one, if the
  // open region there is thinner).
  auto mirror = [&](int i, int j, int k, const int* d, int depth, double& value) {
    for (int s = 1; s < depth; ++s) {  // the cells between must be blocked (and in the local array)
      const int ib = i + s * d[0], jb = j + s * d[1], kb = k + s * d[2];
      if (!e.holds(ib, jb, kb) || !is_blocked(mask, ib, jb, kb)) return false;
    }
    const int iw = i + depth * d[0], jw = j + depth * d[1], kw = k + depth * d[2];  // the first cell beyond the wall
    if (!open(iw, jw, kw)) return false;
    const int im = iw + (depth - 1) * d[0], jm = jw + (depth - 1) * d[1], km = kw + (depth - 1) * d[2];
    value = sign * (open(im, jm, km) ? a[km][jm][im] : a[kw][jw][iw]);
    return true;
  };
  // The nearest wall along an axis, as its depth (0: none within reach); on a tie (a wall on either
  // side) the high side's.
  auto nearest = [&](int i, int j, int k, int axis, double& value) {
    int up[3] = {0, 0, 0}, down[3] = {0, 0, 0};
    up[axis] = 1, down[axis] = -1;
    for (int depth = 1; depth <= gw; ++depth)
      if (mirror(i, j, k, up, depth, value) || mirror(i, j, k, down, depth, value)) return depth;
    return 0;
  };
  // A blocked cell with no open cell within reach along any one axis, diagonally behind the walls
  // where two (or three) obstacles meet in a concave edge or corner of the open region: the mirror
  // across each of those walls in turn, sign once per wall, as the domain's edge and corner ghosts are
  // (mesh/side_ghosts.hpp). The first open cell beyond the walls must be the only open cell of the box
  // between it and the blocked cell; the fewest cells away wins.
  auto across_walls = [&](int i, int j, int k, double& value) {
    int best_distance = 0;
    for (int set = 1; set < (1 << axes); ++set) {  // the axes crossed, two or three
      if ((set & (set - 1)) == 0) continue;  // one axis: done above
      int n_axes = 0, axis_of[3];
      for (int a = 0; a < axes; ++a)
        if (set & (1 << a)) axis_of[n_axes++] = a;
      // Each crossed axis's direction (bit) and depth 1 .. gw.
      const int combos = 1 << n_axes;
      for (int dirs = 0; dirs < combos; ++dirs)
        for (int depths = 0; depths < (n_axes == 2 ? gw * gw : gw * gw * gw); ++depths) {
          int step[3] = {0, 0, 0}, depth[3] = {0, 0, 0}, distance = 0;
          for (int n = 0, rest = depths; n < n_axes; ++n, rest /= gw) {
            const int a = axis_of[n];
            step[a] = (dirs >> n) & 1 ? 1 : -1;
            depth[a] = 1 + rest % gw;
            distance += depth[a];
          }
          if (best_distance > 0 && distance >= best_distance) continue;
          const int iw = i + depth[0] * step[0], jw = j + depth[1] * step[1], kw = k + depth[2] * step[2];
          if (!open(iw, jw, kw)) continue;
          bool walls = true;  // every other cell of the box from (i, j, k) to the open one is blocked
          for (int dk = 0; dk <= depth[2] && walls; ++dk)
            for (int dj = 0; dj <= depth[1] && walls; ++dj)
              for (int di = 0; di <= depth[0] && walls; ++di) {
                if (di == depth[0] && dj == depth[1] && dk == depth[2]) continue;
                const int ib = i + di * step[0], jb = j + dj * step[1], kb = k + dk * step[2];
                walls = e.holds(ib, jb, kb) && is_blocked(mask, ib, jb, kb);
              }
          if (!walls) continue;
          const int im = iw + (depth[0] - 1) * step[0], jm = jw + (depth[1] - 1) * step[1], km = kw + (depth[2] - 1) * step[2];
          const double mirrored = open(im, jm, km) ? a[km][jm][im] : a[kw][jw][iw];
          value = (n_axes == 3 ? sign : 1.0) * mirrored;  // sign^2 across two walls
          best_distance = distance;
        }
    }
    return best_distance > 0;
  };
  // Each blocked cell mirrors across its nearest wall: it is the ghost of the open cell that wall
  // faces. A cell as near to walls along two axes (an obstacle's edge or corner) takes the later
  // axis's, as the domain's edge and corner ghosts do (z's, then y's); a cell nearer to a wall along x
  // keeps x's, as the domain's ghosts behind its west and east sides do.
  for (int k = e.lo[2]; k < e.hi[2]; ++k)
    for (int j = e.lo[1]; j < e.hi[1]; ++j)
      for (int i = e.lo[0]; i < e.hi[0]; ++i) {
        if (!is_blocked(mask, i, j, k)) continue;
        int best = 0;
        double value = 0.0;
        for (int axis = 0; axis < axes; ++axis) {
          double along = 0.0;
          const int depth = nearest(i, j, k, axis, along);
          if (depth > 0 && (best == 0 || depth <= best)) best = depth, value = along;
        }
        if (best > 0 || across_walls(i, j, k, value)) a[k][j][i] = value;
      }
}

}  // namespace granflow

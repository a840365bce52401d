#include "mesh/obstacles.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <vector>

namespace granflow {

namespace {
// Where each blocked cell of the local array takes its value from: the open cell it mirrors, and
// whether the mirror crosses an odd number of walls (then the value takes the sign).
struct MirrorEntry {
  int to[3], from[3];
  bool odd;
};

// The maps of the masks laid out last (mark_cells), by their local vectors' PETSc object ids (unique in
// the process): a mask so laid out is then only read. A mask filled otherwise is mapped at each use.
struct LaidOutMap {
  PetscObjectId mask_id;
  std::vector<MirrorEntry> map;
};
std::vector<LaidOutMap> laid_out_maps;
std::vector<MirrorEntry> mirror_map(const Grid& g, VolumeView mask);
PetscObjectId object_id(Vec v) {
  PetscObjectId id;
  PetscCallAbort(PETSC_COMM_SELF, PetscObjectGetId(reinterpret_cast<PetscObject>(v), &id));
  return id;
}

// The owned values to the local vector, and 0 in the ghosts beyond the domain's boundaries.
void scatter_with_no_obstacle_outside(const Grid& g, Field& f) {
  f.scatter_to_local();
  FieldArray m = local_array(g, f);
  const CellBox e = g.with_ghosts();
  for (int k = e.zs; k < e.ze(); ++k)
    for (int j = e.ys; j < e.ye(); ++j)
      for (int i = e.xs; i < e.xe(); ++i)
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
  // Which blocked cell mirrors which, found once for the mask (the last few masks kept).
  const PetscObjectId id = object_id(mask.local());
  std::erase_if(laid_out_maps, [id](const LaidOutMap& m) { return m.mask_id == id; });
  if (laid_out_maps.size() >= 4) laid_out_maps.erase(laid_out_maps.begin());
  laid_out_maps.push_back({id, mirror_map(g, BlockedView(g, &mask).data())});
  long total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_LONG, MPI_SUM, g.comm());
  return total;
}
}  // namespace

long mark_blocked_cells(const Grid& g, const interface::ShapeUnion& shapes, Field& mask) {
  return mark_cells(g, [&](int i, int j, int) { return shapes.contains(g.xc(i), g.yc(j)); }, mask);
}

long mark_blocked_cells(const Grid& g, const interface::ShapeUnion3& solids, Field& mask,
                        std::span<const long> kept_open) {
  const long nx = g.nx(), ny = g.ny();
  return mark_cells(g, [&](int i, int j, int k) {
    return solids.contains(g.xc(i), g.yc(j), g.zc(k)) &&
           !std::binary_search(kept_open.begin(), kept_open.end(), (k * ny + j) * nx + i);
  }, mask);
}

namespace {
// Each owned cell's 1 + the last of `count` shapes that `contains(n, i, j, k)` its centre (0: none), then the ghosts.
template <class Contains>
void mark_index(const Grid& g, size_t count, Contains contains, Field& index) {
  {
    FieldArray m(g.field_dm(), index.global());
    const auto& b = g.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          double& cell = m.volume()[k][j][i];
          cell = 0.0;
          for (size_t n = 0; n < count; ++n)
            if (contains(n, i, j, k)) cell = double(n + 1);
        }
  }
  scatter_with_no_obstacle_outside(g, index);  // ghosts outside the domain belong to no obstacle
}
}  // namespace

void mark_obstacle_index(const Grid& g, const interface::ShapeUnion& shapes, Field& index) {
  mark_index(g, shapes.size(), [&](size_t n, int i, int j, int) { return shapes.shape_contains(n, g.xc(i), g.yc(j)); },
             index);
}

void mark_obstacle_index(const Grid& g, const interface::ShapeUnion3& solids, Field& index) {
  mark_index(g, solids.size(),
             [&](size_t n, int i, int j, int k) { return solids.shape_contains(n, g.xc(i), g.yc(j), g.zc(k)); }, index);
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

namespace {
std::vector<MirrorEntry> mirror_map(const Grid& g, VolumeView mask) {
  std::vector<MirrorEntry> map;
  const CellBox e = g.with_ghosts();
  const int gw = Grid::ghost_width, axes = g.dimension() == 3 ? 3 : 2;
  auto open = [&](int i, int j, int k) { return e.holds(i, j, k) && !g.outside(i, j, k) && mask[k][j][i] <= 0.5; };
  using Cell = std::array<int, 3>;
  // The mirror of blocked cell c across the wall `depth` cells away along d, if that is where the
  // nearest open cell lies: the open cell depth - 1 beyond the wall (or the first one, if the open
  // region there is thinner).
  auto mirror = [&](const Cell& c, const int* d, int depth, Cell& from) {
    for (int s = 1; s < depth; ++s) {  // the cells between must be blocked (and in the local array)
      const int ib = c[0] + s * d[0], jb = c[1] + s * d[1], kb = c[2] + s * d[2];
      if (!e.holds(ib, jb, kb) || !is_blocked(mask, ib, jb, kb)) return false;
    }
    const Cell w{c[0] + depth * d[0], c[1] + depth * d[1], c[2] + depth * d[2]};  // the first cell beyond the wall
    if (!open(w[0], w[1], w[2])) return false;
    const Cell m{w[0] + (depth - 1) * d[0], w[1] + (depth - 1) * d[1], w[2] + (depth - 1) * d[2]};
    from = open(m[0], m[1], m[2]) ? m : w;
    return true;
  };
  // The nearest wall along an axis, as its depth (0: none within reach); on a tie (a wall on either
  // side) the high side's.
  auto nearest = [&](const Cell& c, int axis, Cell& from) {
    int up[3] = {0, 0, 0}, down[3] = {0, 0, 0};
    up[axis] = 1, down[axis] = -1;
    for (int depth = 1; depth <= gw; ++depth)
      if (mirror(c, up, depth, from) || mirror(c, down, depth, from)) return depth;
    return 0;
  };
  // A blocked cell with no open cell within reach along any one axis, diagonally behind two (or three)
  // walls at an inner edge or corner of the obstacles (a built floor meeting a built wall): the mirror
  // across each of those walls in turn, the sign once per wall, as the domain's edge and corner ghosts are
  // (mesh/side_ghosts.hpp). The first open cell beyond the walls must be the only open cell of the box
  // between it and the blocked cell; the fewest cells away wins.
  auto across_walls = [&](const Cell& c, Cell& from, bool& odd) {
    int best_distance = 0;
    for (int set = 1; set < (1 << axes); ++set) {  // the axes crossed, two or three
      if ((set & (set - 1)) == 0) continue;  // one axis: done before
      int n_axes = 0, axis_of[3];
      for (int a = 0; a < axes; ++a)
        if (set & (1 << a)) axis_of[n_axes++] = a;
      // Each crossed axis's direction (a bit of dirs) and depth, 1 .. gw.
      const int depth_sets = n_axes == 2 ? gw * gw : gw * gw * gw;
      for (int dirs = 0; dirs < (1 << n_axes); ++dirs)
        for (int depths = 0; depths < depth_sets; ++depths) {
          int step[3] = {0, 0, 0}, depth[3] = {0, 0, 0}, distance = 0;
          for (int n = 0, rest = depths; n < n_axes; ++n, rest /= gw) {
            const int a = axis_of[n];
            step[a] = (dirs >> n) & 1 ? 1 : -1;
            depth[a] = 1 + rest % gw;
            distance += depth[a];
          }
          if (best_distance > 0 && distance >= best_distance) continue;
          const Cell w{c[0] + depth[0] * step[0], c[1] + depth[1] * step[1], c[2] + depth[2] * step[2]};
          if (!open(w[0], w[1], w[2])) continue;
          bool walls = true;  // every other cell of the box from c to the open one is blocked
          for (int dk = 0; dk <= depth[2] && walls; ++dk)
            for (int dj = 0; dj <= depth[1] && walls; ++dj)
              for (int di = 0; di <= depth[0] && walls; ++di) {
                if (di == depth[0] && dj == depth[1] && dk == depth[2]) continue;
                const int ib = c[0] + di * step[0], jb = c[1] + dj * step[1], kb = c[2] + dk * step[2];
                walls = e.holds(ib, jb, kb) && is_blocked(mask, ib, jb, kb);
              }
          if (!walls) continue;
          const Cell m{w[0] + (depth[0] - 1) * step[0], w[1] + (depth[1] - 1) * step[1], w[2] + (depth[2] - 1) * step[2]};
          from = open(m[0], m[1], m[2]) ? m : w;
          odd = n_axes == 3;
          best_distance = distance;
        }
    }
    return best_distance > 0;
  };
  // Each blocked cell mirrors across its nearest wall: it is the ghost of the open cell that wall
  // faces. A cell as near to walls along two axes (an obstacle's edge or corner) takes the later
  // axis's, as the domain's edge and corner ghosts do (z's, then y's); a cell nearer to a wall along x
  // keeps x's, as the domain's ghosts behind its west and east sides do.
  for (int k = e.zs; k < e.ze(); ++k)
    for (int j = e.ys; j < e.ye(); ++j)
      for (int i = e.xs; i < e.xe(); ++i) {
        if (!is_blocked(mask, i, j, k)) continue;
        const Cell c{i, j, k};
        int best = 0;
        Cell from{};
        for (int axis = 0; axis < axes; ++axis) {
          Cell along{};
          const int depth = nearest(c, axis, along);
          if (depth > 0 && (best == 0 || depth <= best)) best = depth, from = along;
        }
        bool odd = true;
        if (best > 0 || across_walls(c, from, odd)) map.push_back({{i, j, k}, {from[0], from[1], from[2]}, odd});
      }
  return map;
}
}  // namespace

void mirror_into_blocked(const Grid& g, const Field* mask, double*** a, double sign) {
  if (!mask) return;
  const PetscObjectId id = object_id(mask->local());
  const auto laid_out = std::find_if(laid_out_maps.begin(), laid_out_maps.end(),
                                     [id](const LaidOutMap& m) { return m.mask_id == id; });
  std::vector<MirrorEntry> mapped_now;
  if (laid_out == laid_out_maps.end()) mapped_now = mirror_map(g, BlockedView(g, mask).data());
  for (const MirrorEntry& m : laid_out != laid_out_maps.end() ? laid_out->map : mapped_now)
    a[m.to[2]][m.to[1]][m.to[0]] = (m.odd ? sign : 1.0) * a[m.from[2]][m.from[1]][m.from[0]];
}

}  // namespace granflow

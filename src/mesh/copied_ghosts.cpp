#include "mesh/copied_ghosts.hpp"

#include "mesh/obstacles.hpp"

#include <stdexcept>

namespace granflow {

namespace {
// Along x, then y, then z, each pass over the ghost rows of the passes before, so that an edge's or
// a corner's ghost ends as the nearest cell's copy.
void copy_into_ghost_layers(const Grid& grid, double*** a) {
  const auto& b = grid.owned();
  const int n[3] = {grid.nx(), grid.ny(), grid.nz()}, gw = Grid::ghost_width;
  const int lo[3] = {b.xs - gw, b.ys - gw, b.zs - gw}, hi[3] = {b.xe() + gw, b.ye() + gw, b.ze() + gw};
  for (int axis = 0; axis < 3; ++axis) {
    const bool low = grid.owns_boundary(side_of(axis, -1)), high = grid.owns_boundary(side_of(axis, 1));
    if (!low && !high) continue;
    const int t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
    int p[3];
    for (p[t2] = lo[t2]; p[t2] < hi[t2]; ++p[t2])
      for (p[t1] = lo[t1]; p[t1] < hi[t1]; ++p[t1])
        for (int m = 1; m <= gw; ++m) {
          auto cell = [&](int along) -> double& {
            int q[3] = {p[0], p[1], p[2]};
            q[axis] = along;
            return a[q[2]][q[1]][q[0]];
          };
          if (low) cell(-m) = cell(0);
          if (high) cell(n[axis] - 1 + m) = cell(n[axis] - 1);
        }
  }
}
}  // namespace

void fill_copied_ghosts(const Grid& grid, const Field* blocked, Field& f) {
  f.scatter_to_local();
  FieldArray a = local_array(grid, f);
  if (grid.dimension() == 3) {
    if (blocked) throw std::logic_error("fill_copied_ghosts: obstacles on a mesh of several layers are not implemented");
    copy_into_ghost_layers(grid, a.volume());
    return;
  }
  mirror_into_blocked(grid, BlockedView(grid, blocked).data(), a.data(), 1.0);
  const auto& b = grid.owned();
  const int nx = grid.nx(), ny = grid.ny(), gw = Grid::ghost_width;
  for (int k = 1; k <= gw; ++k)
    for (int j = b.ys - gw; j < b.ye() + gw; ++j) {
      if (grid.owns_boundary(Side::west)) a[j][-k] = a[j][0];
      if (grid.owns_boundary(Side::east)) a[j][nx - 1 + k] = a[j][nx - 1];
    }
  for (int k = 1; k <= gw; ++k)
    for (int i = b.xs - gw; i < b.xe() + gw; ++i) {
      if (b.ys == 0) a[-k][i] = a[0][i];
      if (b.ye() == ny) a[ny - 1 + k][i] = a[ny - 1][i];
    }
}

}  // namespace granflow

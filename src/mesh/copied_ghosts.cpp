#include "mesh/copied_ghosts.hpp"

#include "mesh/obstacles.hpp"

namespace granflow {

void fill_copied_ghosts(const Grid& grid, const Field* blocked, Field& f) {
  f.scatter_to_local();
  FieldArray a = local_array(grid, f);
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

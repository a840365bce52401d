#pragma once
// Ridges one cell wide, lowered to the mesh. A blocked cell between two open cells along one axis is a
// wall one cell thick, whose mirrored ghosts cannot serve both its sides (mesh/obstacles.hpp); an
// elevation model rougher than the cells leaves such ridges wherever a column stands above both its
// neighbours along x or along z. Opening those cells, pass after pass until none is left, lowers each
// such column to the higher of its two neighbours: the terrain the mesh can carry.
#include <array>
#include <functional>
#include <vector>

namespace granflow {

// The cell {i, j, k} of index n of a whole-mesh array (x fastest, then y), as the mask's.
inline std::array<int, 3> cell_of_index(long n, int nx, int ny) {
  return {int(n % nx), int(n / nx % ny), int(n / (long(nx) * ny))};
}

// The blocked cells of `mask` (nx * ny * nz values, x fastest then y, blocked above 0.5) that stand
// between two open cells along x or along z, opened (set to 0) until none that `may_open(index)`
// allows is left; returns their indices, ascending. Cells beyond the domain count as closed, but for
// the other end along x when periodic_x. The cells opened do not depend on the order of opening:
// opening only ever adds open neighbours, so every pass order reaches the same least fixed point.
std::vector<long> open_thin_ridges(int nx, int ny, int nz, bool periodic_x, std::vector<double>& mask,
                                   const std::function<bool(long)>& may_open);

}  // namespace granflow

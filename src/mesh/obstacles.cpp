#include "mesh/obstacles.hpp"

#include <mpi.h>

namespace granflow {

long mark_blocked_cells(const Grid& g, const std::vector<interface::Shape>& shapes, Field& mask) {
  long count = 0;
  {
    FieldArray m(g.field_dm(), mask.global());
    const auto& b = g.owned();
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        m[j][i] = interface::union_contains(shapes, g.xc(i), g.yc(j)) ? 1.0 : 0.0;
        count += m[j][i] > 0.5;
      }
  }
  mask.scatter_to_local();
  {
    // Ghosts outside the domain are not blocked.
    FieldArray m = local_array(g, mask);
    const auto& b = g.owned();
    const int gw = Grid::ghost_width;
    for (int j = b.ys - gw; j < b.ye() + gw; ++j)
      for (int i = b.xs - gw; i < b.xe() + gw; ++i)
        if (i < 0 || i >= g.nx() || j < 0 || j >= g.ny()) m[j][i] = 0.0;
  }
  long total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_LONG, MPI_SUM, g.comm());
  return total;
}

void mirror_into_blocked(const Grid& g, const double* const* mask, double** a, double sign) {
  if (!mask) return;
  const auto& b = g.owned();
  const int gw = Grid::ghost_width;
  const int i_lo = b.xs - gw, i_hi = b.xe() + gw, j_lo = b.ys - gw, j_hi = b.ye() + gw;  // the local array
  auto open = [&](int i, int j) {
    return i >= i_lo && i < i_hi && j >= j_lo && j < j_hi && i >= 0 && i < g.nx() && j >= 0 && j < g.ny() &&
           mask[j][i] <= 0.5;
  };
  // The mirror of blocked cell (i, j) along (di, dj): the wall lies `depth` cells on, 1 or 2.
  auto mirror = [&](int i, int j, int di, int dj, double& value) {
    for (int depth = 1; depth <= gw; ++depth) {
      const int iw = i + depth * di, jw = j + depth * dj;  // the first cell beyond the wall if open
      if (open(iw, jw)) {
        const int im = iw + (depth - 1) * di, jm = jw + (depth - 1) * dj;
        value = sign * (open(im, jm) ? a[jm][im] : a[jw][iw]);
        return true;
      }
      if (!(iw >= i_lo && iw < i_hi && jw >= j_lo && jw < j_hi) || !is_blocked(mask, iw, jw)) return false;
    }
    return false;
  };
  for (int pass = 0; pass < 2; ++pass)
    for (int j = j_lo; j < j_hi; ++j)
      for (int i = i_lo; i < i_hi; ++i) {
        if (!is_blocked(mask, i, j)) continue;
        double value;
        const int di = pass == 0 ? 1 : 0, dj = 1 - di;
        if (mirror(i, j, di, dj, value) || mirror(i, j, -di, -dj, value)) a[j][i] = value;
      }
}

}  // namespace granflow

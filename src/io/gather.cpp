#include "io/gather.hpp"

#include <algorithm>

namespace granflow {

std::vector<double> gather_to_root(const Grid& grid, Vec global) {
  MPI_Comm comm = grid.comm();
  Vec natural, zero;
  VecScatter scatter;
  PetscCallAbort(comm, DMDACreateNaturalVector(grid.field_dm(), &natural));
  PetscCallAbort(comm, DMDAGlobalToNaturalBegin(grid.field_dm(), global, INSERT_VALUES, natural));
  PetscCallAbort(comm, DMDAGlobalToNaturalEnd(grid.field_dm(), global, INSERT_VALUES, natural));
  PetscCallAbort(comm, VecScatterCreateToZero(natural, &scatter, &zero));
  PetscCallAbort(comm, VecScatterBegin(scatter, natural, zero, INSERT_VALUES, SCATTER_FORWARD));
  PetscCallAbort(comm, VecScatterEnd(scatter, natural, zero, INSERT_VALUES, SCATTER_FORWARD));
  std::vector<double> out;
  PetscInt n;
  VecGetLocalSize(zero, &n);
  if (n > 0) {
    const double* a;
    VecGetArrayRead(zero, &a);
    out.assign(a, a + n);
    VecRestoreArrayRead(zero, &a);
  }
  VecScatterDestroy(&scatter);
  VecDestroy(&zero);
  VecDestroy(&natural);
  return out;
}

std::vector<double> gather_to_root(const Grid& grid, const Field& field) { return gather_to_root(grid, field.global()); }

namespace {
// Index of the cell centre at or below x and the weight of the next one.
void bracket(int n, double x, auto centre, int& i0, double& w) {
  if (x <= centre(0)) { i0 = 0; w = 0.0; return; }
  if (x >= centre(n - 1)) { i0 = std::max(n - 2, 0); w = n > 1 ? 1.0 : 0.0; return; }
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (centre(mid) <= x ? lo : hi) = mid;
  }
  i0 = lo;
  w = (x - centre(lo)) / (centre(lo + 1) - centre(lo));
}
}  // namespace

double sample_bilinear(const Grid& grid, const std::vector<double>& v, double x, double y) {
  const int nx = grid.nx(), ny = grid.ny();
  int i0, j0;
  double wx, wy;
  bracket(nx, x, [&](int i) { return grid.xc(i); }, i0, wx);
  bracket(ny, y, [&](int j) { return grid.yc(j); }, j0, wy);
  const int i1 = std::min(i0 + 1, nx - 1), j1 = std::min(j0 + 1, ny - 1);
  auto at = [&](int i, int j) { return v[size_t(j) * nx + i]; };
  return (1 - wy) * ((1 - wx) * at(i0, j0) + wx * at(i1, j0)) + wy * ((1 - wx) * at(i0, j1) + wx * at(i1, j1));
}

}  // namespace granflow

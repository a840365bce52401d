#include "mesh/gather.hpp"

#include "mesh/largest.hpp"

namespace granflow {

namespace {
std::vector<double> gather(const Grid& grid, Vec global, bool to_all) {
  MPI_Comm comm = grid.comm();
  Vec natural, gathered;
  VecScatter scatter;
  PetscCallAbort(comm, DMDACreateNaturalVector(grid.field_dm(), &natural));
  PetscCallAbort(comm, DMDAGlobalToNaturalBegin(grid.field_dm(), global, INSERT_VALUES, natural));
  PetscCallAbort(comm, DMDAGlobalToNaturalEnd(grid.field_dm(), global, INSERT_VALUES, natural));
  if (to_all) PetscCallAbort(comm, VecScatterCreateToAll(natural, &scatter, &gathered));
  else PetscCallAbort(comm, VecScatterCreateToZero(natural, &scatter, &gathered));
  PetscCallAbort(comm, VecScatterBegin(scatter, natural, gathered, INSERT_VALUES, SCATTER_FORWARD));
  PetscCallAbort(comm, VecScatterEnd(scatter, natural, gathered, INSERT_VALUES, SCATTER_FORWARD));
  std::vector<double> out;
  PetscInt n;
  PetscCallAbort(comm, VecGetLocalSize(gathered, &n));
  if (n > 0) {
    const double* a;
    PetscCallAbort(comm, VecGetArrayRead(gathered, &a));
    out.assign(a, a + n);
    PetscCallAbort(comm, VecRestoreArrayRead(gathered, &a));
  }
  PetscCallAbort(comm, VecScatterDestroy(&scatter));
  PetscCallAbort(comm, VecDestroy(&gathered));
  PetscCallAbort(comm, VecDestroy(&natural));
  return out;
}
}  // namespace

std::vector<double> gather_to_root(const Grid& grid, const Field& field) { return gather(grid, field.global(), false); }

std::vector<double> gather_to_all(const Grid& grid, const Field& field) { return gather(grid, field.global(), true); }

double max_abs(MPI_Comm comm, Vec v) {
  PetscInt n = 0;
  const PetscScalar* a = nullptr;
  PetscCallAbort(comm, VecGetLocalSize(v, &n));
  PetscCallAbort(comm, VecGetArrayRead(v, &a));
  double largest = 0.0;
  for (PetscInt k = 0; k < n; ++k) largest = larger_or_nan(largest, std::abs(a[k]));
  PetscCallAbort(comm, VecRestoreArrayRead(v, &a));
  return mpi_max(comm, largest);
}

}  // namespace granflow

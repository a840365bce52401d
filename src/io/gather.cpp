#include "io/gather.hpp"

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

}  // namespace granflow

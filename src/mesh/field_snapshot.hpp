#pragma once
// Copies of a fixed list of fields, ghosts included, to take a step again from where it started.
#include <span>
#include <vector>

#include "mesh/field.hpp"
#include "mesh/petsc_handle.hpp"

namespace granflow {

class FieldSnapshot {
 public:
  FieldSnapshot() = default;

  // The same fields, in the same order, on every save and restore.
  void save(std::span<Field* const> fields) {
    size_t k = 0;
    for (const Field* f : fields) {
      if (k == copies_.size()) PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(f->local(), copies_.emplace_back().put()));
      PetscCallAbort(PETSC_COMM_WORLD, VecCopy(f->local(), copies_[k++]));  // local vectors hold the ghosts (boundary conditions) too
    }
  }
  void restore(std::span<Field* const> fields) const {
    size_t k = 0;
    for (Field* f : fields) {
      PetscCallAbort(PETSC_COMM_WORLD, VecCopy(copies_.at(k++), f->local()));
      f->gather_from_local();
    }
  }

 private:
  std::vector<OwnedVec> copies_;
};

}  // namespace granflow

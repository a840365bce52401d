#pragma once
// Entry (i, j, k, unknown) of the rank's part of a vector of several unknowns per cell, interleaved
// cell by cell as a DMDA of that many degrees of freedom lays them out (the coupled solve's (u, v, p)
// or (u, v, w, p)), on a mesh of any dimension: one access for the planar and the 3D DMDA, whose
// DMDAVecGetArrayDOF arrays differ in rank.
#include <petscvec.h>

#include <cstddef>

#include "mesh/cell_box.hpp"

namespace granflow {

class CellUnknowns {
 public:
  CellUnknowns(MPI_Comm comm, Vec v, const CellBox& owned, int per_cell)
      : comm_(comm), v_(v), b_(owned), per_cell_(per_cell) {
    PetscCallAbort(comm_, VecGetArray(v_, &a_));
  }
  ~CellUnknowns() { PetscCallAbort(comm_, VecRestoreArray(v_, &a_)); }
  CellUnknowns(const CellUnknowns&) = delete;
  CellUnknowns& operator=(const CellUnknowns&) = delete;

  double& operator()(int i, int j, int k, int unknown) const {
    return a_[((std::size_t(k - b_.zs) * b_.ym + (j - b_.ys)) * b_.xm + (i - b_.xs)) * per_cell_ + unknown];
  }

 private:
  MPI_Comm comm_;
  Vec v_;
  CellBox b_;
  int per_cell_;
  PetscScalar* a_ = nullptr;
};

}  // namespace granflow

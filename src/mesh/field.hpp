#pragma once
// A cell field on the grid: one global Vec (owned values, what solvers and writers see) and one
// local Vec (owned plus ghosts, what stencils read). Arrays are indexed [k][j][i] with global indices;
// on a mesh of one layer along z, [j][i] (and data()) is its one plane, k = 0.
// The whole-field operations (set, copy_from, combine, ...) act on both, so ghosts stay current.
#include <petscdmda.h>

#include "mesh/grid.hpp"
#include "mesh/petsc_handle.hpp"

namespace granflow {

class Field {
 public:
  explicit Field(const Grid& grid) : dm_(grid.field_dm()) {
    PetscCallAbort(PETSC_COMM_WORLD, DMCreateGlobalVector(dm_, global_.put()));
    PetscCallAbort(PETSC_COMM_WORLD, DMCreateLocalVector(dm_, local_.put()));
  }
  Field(const Field&) = delete;
  Field& operator=(const Field&) = delete;

  Vec global() const { return global_; }
  Vec local() const { return local_; }
  DM dm() const { return dm_; }
  // Owned values -> local ghosts (interior ghosts only; domain-boundary ghosts are the caller's).
  void scatter_to_local() {
    PetscCallAbort(PETSC_COMM_WORLD, DMGlobalToLocalBegin(dm_, global_, INSERT_VALUES, local_));
    PetscCallAbort(PETSC_COMM_WORLD, DMGlobalToLocalEnd(dm_, global_, INSERT_VALUES, local_));
  }
  // Local owned values -> global. Copied block by block: PETSc's DMLocalToGlobal with INSERT_VALUES
  // refuses a periodic axis that one rank holds whole.
  void gather_from_local() {
    PetscInt xs, ys, zs, xm, ym, zm;
    PetscCallAbort(PETSC_COMM_WORLD, DMDAGetCorners(dm_, &xs, &ys, &zs, &xm, &ym, &zm));
    double ***g, ***l;
    PetscCallAbort(PETSC_COMM_WORLD, DMDAVecGetArray(dm_, global_, &g));
    PetscCallAbort(PETSC_COMM_WORLD, DMDAVecGetArray(dm_, local_, &l));
    for (PetscInt k = zs; k < zs + zm; ++k)
      for (PetscInt j = ys; j < ys + ym; ++j)
        for (PetscInt i = xs; i < xs + xm; ++i) g[k][j][i] = l[k][j][i];
    PetscCallAbort(PETSC_COMM_WORLD, DMDAVecRestoreArray(dm_, local_, &l));
    PetscCallAbort(PETSC_COMM_WORLD, DMDAVecRestoreArray(dm_, global_, &g));
  }
  void set(double value) {
    PetscCallAbort(PETSC_COMM_WORLD, VecSet(global_, value));
    PetscCallAbort(PETSC_COMM_WORLD, VecSet(local_, value));
  }
  void copy_from(const Field& other) {
    PetscCallAbort(PETSC_COMM_WORLD, VecCopy(other.global_, global_));
    PetscCallAbort(PETSC_COMM_WORLD, VecCopy(other.local_, local_));
  }
  // this = alpha a + beta b
  void combine(double alpha, const Field& a, double beta, const Field& b) {
    PetscCallAbort(PETSC_COMM_WORLD, VecAXPBYPCZ(global_, alpha, beta, 0.0, a.global_, b.global_));
    PetscCallAbort(PETSC_COMM_WORLD, VecAXPBYPCZ(local_, alpha, beta, 0.0, a.local_, b.local_));
  }
  // this = max(this, other), value by value
  void max_with(const Field& other) {
    PetscCallAbort(PETSC_COMM_WORLD, VecPointwiseMax(global_, global_, other.global_));
    PetscCallAbort(PETSC_COMM_WORLD, VecPointwiseMax(local_, local_, other.local_));
  }

 private:
  DM dm_;
  OwnedVec global_;
  OwnedVec local_;
};

namespace detail {
// Whether the DMDA has one layer along z, whose arrays are then the plane [0][j][i].
inline bool one_layer(DM dm) {
  PetscInt layers = 1;
  PetscCallAbort(PETSC_COMM_WORLD, DMDAGetInfo(dm, nullptr, nullptr, nullptr, &layers, nullptr, nullptr, nullptr,
                                               nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
  return layers == 1;
}
}  // namespace detail

// RAII access to a local (ghosted) or global vector as an array [k][j][i] in global indices (volume()),
// or, on a mesh of one layer along z, as its plane [j][i] (operator[], data()). On a mesh of several
// layers the plane is null: a 2D kernel there fails at once rather than reading some layer.
class FieldArray {
 public:
  FieldArray(DM dm, Vec v) : dm_(dm), v_(v) {
    PetscCallAbort(PETSC_COMM_WORLD, DMDAVecGetArray(dm_, v_, &a_));
    if (detail::one_layer(dm_)) plane_ = a_[0];
  }
  ~FieldArray() { DMDAVecRestoreArray(dm_, v_, &a_); }
  FieldArray(const FieldArray&) = delete;
  FieldArray& operator=(const FieldArray&) = delete;
  double* operator[](int j) const { return plane_[j]; }
  double** data() const { return plane_; }
  double*** volume() const { return a_; }

 private:
  DM dm_;
  Vec v_;
  double*** a_ = nullptr;
  double** plane_ = nullptr;
};

// Read-only FieldArray.
class ConstFieldArray {
 public:
  ConstFieldArray(DM dm, Vec v) : dm_(dm), v_(v) {
    PetscCallAbort(PETSC_COMM_WORLD, DMDAVecGetArrayRead(dm_, v_, &a_));
    if (detail::one_layer(dm_)) plane_ = volume()[0];
  }
  ~ConstFieldArray() { DMDAVecRestoreArrayRead(dm_, v_, &a_); }
  ConstFieldArray(const ConstFieldArray&) = delete;
  ConstFieldArray& operator=(const ConstFieldArray&) = delete;
  const double* operator[](int j) const { return plane_[j]; }
  const double* const* data() const { return plane_; }
  const double* const* const* volume() const { return static_cast<const double* const* const*>(a_); }

 private:
  DM dm_;
  Vec v_;
  void* a_ = nullptr;
  const double* const* plane_ = nullptr;
};

// A read-only array [k][j][i] as ConstFieldArray::volume() gives it; on a planar mesh k = 0.
using VolumeView = const double* const* const*;
inline double at(VolumeView a, int i, int j, int k) { return a[k][j][i]; }
// A plane [j][i] seen as a volume of one layer, for 2D callers of kernels written for any dimension.
struct PlaneAsVolume {
  explicit PlaneAsVolume(const double* const* plane) : layers{plane} {}
  operator VolumeView() const { return layers; }
  const double* const* layers[1];
};

inline FieldArray local_array(const Grid& g, Field& f) { return FieldArray(g.field_dm(), f.local()); }
inline ConstFieldArray local_read(const Grid& g, const Field& f) { return ConstFieldArray(g.field_dm(), f.local()); }

}  // namespace granflow

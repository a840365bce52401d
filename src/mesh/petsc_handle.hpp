#pragma once
// Ownership of one PETSc object (a Mat, Vec, KSP, DM or MatNullSpace): destroyed with its owner, also
// when the owner's constructor throws after making it, and passed to PETSc's calls as the raw handle.
#include <petscdm.h>
#include <petscksp.h>

#include <utility>

namespace granflow {

template <class Handle, PetscErrorCode (*destroy)(Handle*)>
class PetscHandle {
 public:
  PetscHandle() = default;
  ~PetscHandle() { reset(); }
  PetscHandle(const PetscHandle&) = delete;
  PetscHandle& operator=(const PetscHandle&) = delete;
  PetscHandle(PetscHandle&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  PetscHandle& operator=(PetscHandle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }

  operator Handle() const { return handle_; }  // NOLINT: PETSc's calls take the raw handle
  Handle get() const { return handle_; }
  // Destroys the object held, if any, and gives the address a PETSc create call writes the new one to:
  // KSPCreate(comm, ksp.put()).
  Handle* put() {
    reset();
    return &handle_;
  }
  // Destroys the object held, once: a destroy that failed part-way (a library's state left half made
  // after a failed solve) is not tried again, which would read what it already freed.
  void reset() {
    if (handle_) destroy(&handle_);
    handle_ = nullptr;
  }

 private:
  Handle handle_ = nullptr;
};

using OwnedMat = PetscHandle<Mat, MatDestroy>;
using OwnedVec = PetscHandle<Vec, VecDestroy>;
using OwnedKsp = PetscHandle<KSP, KSPDestroy>;
using OwnedDm = PetscHandle<DM, DMDestroy>;
using OwnedNullSpace = PetscHandle<MatNullSpace, MatNullSpaceDestroy>;

}  // namespace granflow

#pragma once
// What granflow says of PETSc: its errors as one line, options nothing read, and the files its
// options name that it could not use, each found before PETSc would stop with its own trace.
#include <petscsys.h>

#include <set>
#include <string>
#include <vector>

namespace granflow {

// Options given to PETSc that nothing read (a misspelt name, a solver prefix that does not exist),
// one warning each on rank 0: PETSc itself ignores them silently. With `judged`, only those among it
// (`granflow check`, which makes no solver of the run's: options_left_by_solvers).
void warn_unused_petsc_options(int rank, const std::set<std::string>* judged = nullptr);

// An error that ends the run and that every rank may meet alike (and abort on): said by rank 0, and by
// another rank only if the abort has not come two seconds later, with its rank.
void say_error_once(const std::string& what);

// PETSc's error handler, pushed once with PetscPushErrorHandler before PetscInitialize: while PETSc
// starts, its first error (in an options file: a line it cannot parse) is kept as one line for the
// message that PETSc could not start (`startup_petsc_error_text`); once `petsc_has_started` has been
// called, an error is said as one line (PETSc would print its whole trace) and ends the run with status
// 1. One handler for both, never popped: a handler pushed before PetscInitialize is allocated before
// PETSc's memory tracing (-malloc_debug) starts, and freeing it after would be reported as corruption.
PetscErrorCode granflow_petsc_error(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                                    PetscErrorType type, const char* message, void*);
void petsc_has_started();
const std::string& startup_petsc_error_text();

// The first options file PETSc could not read, or -log_view file it could not write, among the
// words of PETSc options from `source` (--petsc, or PETSC_OPTIONS from the environment), as a
// message naming it; empty when every such file can be used.
std::string unusable_petsc_file(const std::vector<std::string>& words, const std::string& source = "--petsc");

}  // namespace granflow

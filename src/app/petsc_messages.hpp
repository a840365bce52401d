#pragma once
// What granflow says of PETSc: its errors as one line, options nothing read, and the files its
// options name that it could not use, each found before PETSc would stop with its own trace.
#include <petscsys.h>

#include <string>
#include <vector>

namespace granflow {

// Options given to PETSc that nothing read (a misspelt name, a solver prefix that does not exist),
// one warning each on rank 0: PETSc itself ignores them silently.
void warn_unused_petsc_options(int rank);

// An error that ends the run and that every rank may meet alike (and abort on): said by rank 0, and by
// another rank only if the abort has not come two seconds later, with its rank.
void say_error_once(const std::string& what);

// PETSc's error handler: the error as one line (PETSc would print its whole trace), then the end of
// the run with status 1. Pushed with PetscPushErrorHandler.
PetscErrorCode one_line_petsc_error(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                                    PetscErrorType type, const char* message, void*);

// PETSc's first error while it starts (in an options file: a line it cannot parse), kept as one line
// for the message that PETSc could not start, instead of PETSc's trace. Pushed with
// PetscPushErrorHandler before PetscInitialize; `startup_petsc_error_text` returns what it kept.
PetscErrorCode keep_startup_petsc_error(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                                        PetscErrorType type, const char* message, void*);
const std::string& startup_petsc_error_text();

// The first options file PETSc could not read, or -log_view file it could not write, among the
// words of PETSc options from `source` (--petsc, or PETSC_OPTIONS from the environment), as a
// message naming it; empty when every such file can be used.
std::string unusable_petsc_file(const std::vector<std::string>& words, const std::string& source = "--petsc");

}  // namespace granflow

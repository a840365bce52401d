#pragma once
// Numerical LU factorisations so far in this process, by PETSc's event log (MUMPS's and PETSc's own
// alike): tests that a solve reuses a factorisation count them, since reuse changes no result.
#include <petsclog.h>

namespace granflow::test {

inline int lu_factorisations() {
  PetscBool active;
  PetscLogIsActive(&active);
  if (!active) PetscLogDefaultBegin();  // counts from here on
  PetscLogEvent event;
  PetscLogEventGetId("MatLUFactorNum", &event);
  PetscEventPerfInfo info{};
  PetscLogEventGetPerfInfo(0, event, &info);  // the main stage
  return info.count;
}

}  // namespace granflow::test

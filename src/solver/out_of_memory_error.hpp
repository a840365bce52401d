#pragma once
// Thrown (on every rank alike) when a linear solver's factorisation runs out of memory: no shorter
// step needs less, so the run stops at once (status 1, as for PETSc's own out-of-memory error) rather
// than retrying the step as for a solve that diverged.
#include <stdexcept>

namespace granflow {
struct OutOfMemoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
}  // namespace granflow

#pragma once
// Thrown (on every rank alike) when the solution stops being finite or bounded; the last output stays
// as written.
#include <stdexcept>

namespace granflow {
struct DivergenceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
}  // namespace granflow

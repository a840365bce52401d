#pragma once
// Thrown (on every rank alike) when the solution stops being finite or bounded; the last output stays
// as written.
#include <stdexcept>

namespace granflow {
// What the message says of the output; a run that replaces an earlier one and diverges before its first
// step puts the earlier run back instead, and says so in place of this (app/run_case.cpp).
inline constexpr const char* last_output_kept = "the last good output is kept";


struct DivergenceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A linear solve that ended without converging (a breakdown, a residual that grew or became NaN; not
// one that stopped at its iteration count): a shorter step may solve, so the step is taken again.
struct LinearSolveFailure : DivergenceError {
  using DivergenceError::DivergenceError;
};
}  // namespace granflow

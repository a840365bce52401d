#pragma once
// A maximum in which a NaN wins. A Courant number or a change that is NaN has to reach the checks
// that retry or stop a step, but std::max(x, NaN) is x.
#include <limits>

namespace granflow {

// The larger of a and b; NaN if either is.
constexpr double larger_or_nan(double a, double b) noexcept {
  return (a != a || b != b) ? std::numeric_limits<double>::quiet_NaN() : (a < b ? b : a);
}

// Whether `candidate` takes the place of `running` in a search for the largest value and where it
// lies: if larger, or NaN; never once `running` is NaN (the first NaN found stays found).
constexpr bool takes_the_lead(double candidate, double running) noexcept {
  return running == running && !(candidate <= running);
}

}  // namespace granflow

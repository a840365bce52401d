#pragma once
// An error in a case file or its overrides: one message that names the key and what is wrong.
#include <stdexcept>
#include <string>

namespace granflow {
struct CaseError : std::runtime_error {
  explicit CaseError(const std::string& what) : std::runtime_error(what) {}
};
}  // namespace granflow

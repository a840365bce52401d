#pragma once
// Advice on a valid case whose numerics are known not to give what such a case is run for. The case
// still runs; `granflow check` and `granflow run` print each line as a warning.
#include <string>
#include <vector>

#include "io/case_file.hpp"

namespace granflow {

// One line per piece of advice, empty when there is none.
std::vector<std::string> case_advice(const CaseConfig& config);

}  // namespace granflow

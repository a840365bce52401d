#pragma once
// `granflow stability`: the factor of safety of a case by strength reduction (solver/strength_reduction.hpp),
// its trials into one output directory, from the case file to the verdict.
#include <string>
#include <vector>

#include "solver/strength_reduction.hpp"

namespace granflow {

// Runs the trials into out_dir (out/<case name>_stability if empty), one subdirectory each, and writes
// stability.csv there; prints a line per trial and the factor of safety. Refuses a directory that holds
// an earlier analysis unless overwrite (which removes its stability.csv and trial directories only) or
// restart: the earlier analysis, of the same case and displacement limit, is continued; its trials in
// stability.csv are taken as they are, and a trial it did not finish is run again. Collective on
// PETSC_COMM_WORLD; throws what the trials meet. Returns the exit status: 0 when a factor was
// bracketed, 1 when none was within the search's range.
int run_stability(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
                  bool overwrite, bool restart, const StrengthReductionSettings& settings);

}  // namespace granflow

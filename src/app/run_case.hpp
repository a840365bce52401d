#pragma once
// `granflow run`: a case run into its output directory, from the case file to the summary lines.
#include <string>
#include <vector>

#include "io/case_file.hpp"

namespace granflow {

// The solvers' method names and PETSc's options for the solvers the run makes, checked by PETSc itself
// (which must be initialised); throws CaseError.
void check_solver_options(const CaseConfig& c);

// Runs the case into out_dir (out/<case name> if empty): refuses a directory that holds an earlier run
// (unless restart or overwrite), holds the directory alone while it runs, continues from its
// checkpoint (restart) or replaces the earlier run (overwrite), and prints the banner and the
// summary. Collective on PETSC_COMM_WORLD; throws what the run meets.
int run_case(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
             bool restart, bool overwrite);

}  // namespace granflow

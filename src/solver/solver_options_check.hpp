#pragma once
// What is wrong with a linear solver's settings and PETSc's options for it, found before a run makes
// its solvers (granflow check and run alike): unknown method names, options PETSc refuses, tolerances
// out of the case file's range, factorisations that cannot be made, options no solver reads.
#include <petscksp.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "solver/linear_solver.hpp"

namespace granflow {

// What is wrong with the settings' method names ("" if PETSc knows both): a misspelt ksp_type or
// pc_type is found before a run starts, not as a PETSc error trace inside it. Needs PETSc initialised.
std::string unknown_method(const LinearSolverSettings& settings);

// What in PETSc's options (--petsc, PETSC_OPTIONS, options files) would stop the run's solver `prefix`
// from being made with `settings` ("" if nothing): an option PETSc refuses (an unknown
// -PREFIX_pc_type), or a tolerance outside the case file's range. So `granflow check` finds what
// `granflow run` refuses before it starts. Needs PETSc initialised and the methods known.
std::string petsc_options_problem(const std::string& prefix, const LinearSolverSettings& settings);

// PETSc's options (without their '-') that none of the solvers `made` (prefix and settings, as a run
// makes them) reads when made and set up on a small matrix, where a factorisation package and AMG read
// theirs: what `granflow check` warns of as `run` does at its end. Monitors and viewers are not made
// (checking must not write): among them are only a solver's (ksp_, pc_) under no made solver's prefix. Nothing is among
// them if a solver cannot be set up there. Options that PETSc itself reads elsewhere (-log_view) are.
// Needs PETSc initialised.
std::set<std::string> options_left_by_solvers(const std::vector<std::pair<std::string, LinearSolverSettings>>& made);

// The case file's table of a solver from its options prefix (momentum_x and momentum_y: momentum).
std::string solver_table_name(const std::string& prefix);

// PETSc's text for an error code, with the code.
std::string petsc_error_text(PetscErrorCode error);

// Where a tolerance of `ksp`, as PETSc's options may have set it, is outside the case file's range
// ("" if none): PETSc takes any tolerance its options give (-PREFIX_ksp_rtol 2 stops every solve before
// its first iteration, a negative -PREFIX_ksp_max_it at once), so the case file's ranges hold for them too.
std::string tolerance_problem(KSP ksp, const std::string& prefix);

}  // namespace granflow

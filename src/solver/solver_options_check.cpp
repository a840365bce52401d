#include "solver/solver_options_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace granflow {

std::string solver_table_name(const std::string& prefix) {
  return prefix.rfind("momentum", 0) == 0 ? "momentum" : prefix;
}

std::string petsc_error_text(PetscErrorCode error) {
  const char* text = nullptr;
  PetscErrorMessage(error, &text, nullptr);
  return text ? fmt::format("{}, PETSc error {}", text, int(error)) : fmt::format("PETSc error {}", int(error));
}

std::string tolerance_problem(KSP ksp, const std::string& prefix) {
  PetscReal rtol, atol, divtol;
  PetscInt max_it;
  KSPGetTolerances(ksp, &rtol, &atol, &divtol, &max_it);
  const std::string table = solver_table_name(prefix);
  auto outside = [&](const char* key, const char* option, double value, const char* range) {
    return fmt::format("linear solver '{}': {} = {} (solver.{}.{}, or PETSc's -{}_ksp_{}) must be {}", prefix, key,
                       value, table, key, prefix, option, range);
  };
  if (!(rtol >= 0 && rtol < 1)) return outside("rtol", "rtol", rtol, "within [0, 1)");
  if (!(atol >= 0 && std::isfinite(atol))) return outside("atol", "atol", atol, "zero or positive");
  if (max_it < 1) return outside("max_iterations", "max_it", double(max_it), "at least 1");
  if (!(divtol >= 1))
    return fmt::format("linear solver '{}': PETSc's -{}_ksp_divtol = {} must be at least 1 (a solve whose residual "
                       "grows that many times is taken for diverged)", prefix, prefix, divtol);
  return {};
}

namespace {
// A copy of PETSc's options without those that open a file or print (-..._monitor..., -..._view...):
// checking the options must not write, or empty, what the run would write. A name starts with '-' and a
// letter; a value may start with '-' and a digit (-5).
PetscOptions options_without_viewers(std::vector<std::string>* left_out = nullptr) {
  char* all = nullptr;
  PetscOptionsGetAll(nullptr, &all);
  std::istringstream words(all ? all : "");
  PetscFree(all);
  std::string kept, word;
  bool keep = true;
  while (words >> word) {
    if (word.size() > 1 && word[0] == '-' && std::isalpha(static_cast<unsigned char>(word[1]))) {
      keep = word.find("_monitor") == std::string::npos && word.find("_view") == std::string::npos &&
             word.rfind("-monitor", 0) != 0 && word.rfind("-view", 0) != 0;
      if (!keep && left_out) left_out->push_back(word.substr(1));
    }
    if (keep) kept += word + " ";
  }
  PetscOptions options;
  PetscOptionsCreate(&options);
  PetscOptionsInsertString(options, kept.c_str());
  return options;
}

// The solver `prefix` as LinearSolver makes it, on `options` (a copy of PETSc's, so that checking reads
// none of the run's): its methods and tolerances, and the default factorisation package
// (default_factorisation_package) set in the copy where the options name none, its name then added to
// `defaults`. *ksp is the caller's to destroy, however far the making came; the first error is returned.
PetscErrorCode make_solver_on(PetscOptions options, const std::string& prefix, const LinearSolverSettings& s, KSP* ksp,
                              std::set<std::string>& defaults) {
  PC pc = nullptr;
  PetscErrorCode error = KSPCreate(PETSC_COMM_SELF, ksp);
  if (!error) error = PetscObjectSetOptions(reinterpret_cast<PetscObject>(*ksp), options);
  if (!error) error = KSPSetOptionsPrefix(*ksp, (prefix + "_").c_str());
  if (!error) error = KSPSetType(*ksp, s.ksp_type.c_str());
  if (!error) error = KSPGetPC(*ksp, &pc);
  if (!error) error = PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), options);
  if (!error) error = PCSetType(pc, s.pc_type.c_str());
  if (!error) error = KSPSetTolerances(*ksp, s.rtol, s.atol, PETSC_DEFAULT, s.max_iterations);
  if (const char* package = default_factorisation_package(s); !error && package) {
    const std::string option = "-" + prefix + "_pc_factor_mat_solver_type";
    PetscBool given = PETSC_FALSE;
    error = PetscOptionsHasName(options, nullptr, option.c_str(), &given);
    if (!error && !given) error = PetscOptionsSetValue(options, option.c_str(), package);
    if (!error && !given) defaults.insert(option.substr(1));
  }
  return error;
}

// What PETSc's options (--petsc, an options file, PETSC_OPTIONS) make of a solver's factorisation that
// PETSc accepts there but cannot carry out: a Cholesky factor of a matrix that is not symmetric (the
// case file refuses it as pc_type), a factorisation package PETSc does not have, or one that does not
// make this factor of this matrix (MUMPS no ILU, a serial package on several ranks). Empty if none.
std::string factorisation_problem(PC pc, const std::string& prefix) {
  PCType type = nullptr;
  PCGetType(pc, &type);
  if (!type) return {};
  const std::string_view t(type);
  const bool symmetric_matrix = prefix == "pressure";
  if (!symmetric_matrix && (t == PCCHOLESKY || t == PCICC))
    return fmt::format("linear solver '{}': PETSc's options make its pc_type '{}', which needs a symmetric positive "
                       "definite matrix, and the {} is not symmetric (use lu)",
                       prefix, t, prefix == "coupled" ? "coupled velocity-pressure system" : "momentum matrix");
  const MatFactorType factor = t == PCLU ? MAT_FACTOR_LU : t == PCCHOLESKY ? MAT_FACTOR_CHOLESKY
                             : t == PCILU ? MAT_FACTOR_ILU : t == PCICC ? MAT_FACTOR_ICC : MAT_FACTOR_NONE;
  if (factor == MAT_FACTOR_NONE) return {};
  MatSolverType package = nullptr;
  PCFactorGetMatSolverType(pc, &package);
  if (!package) return {};
  MatInitializePackage();
  int ranks = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  PetscBool found = PETSC_FALSE, takes_the_matrix = PETSC_FALSE;
  MatSolverFunction make_factor = nullptr;  // none where the package does not make this factor
  MatSolverTypeGet(package, ranks == 1 ? MATSEQAIJ : MATMPIAIJ, factor, &found, &takes_the_matrix, &make_factor);
  const bool does_this = takes_the_matrix && make_factor;
  if (!found)
    return fmt::format("linear solver '{}': PETSc's options name the factorisation package '{}', which this PETSc "
                       "does not have (mumps, petsc, superlu and umfpack are the usual ones)", prefix, package);
  if (!does_this) {
    const bool incomplete = factor == MAT_FACTOR_ILU || factor == MAT_FACTOR_ICC;
    const std::string option = fmt::format("-{}_pc_factor_mat_solver_type", prefix);
    const std::string other =
        ranks == 1   ? fmt::format("name another with {}, e.g. petsc", option)
        : incomplete ? std::string("on several ranks an incomplete factor is pc_type bjacobi's, on each rank's block")
                     : fmt::format("name a parallel one with {}, mumps or superlu_dist", option);
    return fmt::format("linear solver '{}': its factorisation package '{}' does not do pc_type '{}'{} ({})", prefix,
                       package, t, ranks == 1 ? "" : fmt::format(" on {} ranks", ranks), other);
  }
  return {};
}
}  // namespace

std::string petsc_options_problem(const std::string& prefix, const LinearSolverSettings& s) {
  PetscOptions options = options_without_viewers();
  KSP ksp = nullptr;
  std::set<std::string> defaults;
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // what PETSc refuses is told in one line, below
  PetscErrorCode error = make_solver_on(options, prefix, s, &ksp, defaults);
  if (!error) error = KSPSetFromOptions(ksp);
  PetscPopErrorHandler();
  std::string problem;
  if (error) {
    char* specific = nullptr;
    PetscErrorMessage(error, nullptr, &specific);
    problem = fmt::format("linear solver '{}': PETSc refuses its options: {}", prefix,
                          specific && *specific ? std::string(specific) : petsc_error_text(error));
  } else {
    PC pc = nullptr;
    KSPGetPC(ksp, &pc);
    problem = factorisation_problem(pc, prefix);
    if (problem.empty()) problem = tolerance_problem(ksp, prefix);
  }
  KSPDestroy(&ksp);
  PetscOptionsDestroy(&options);
  return problem;
}

std::set<std::string> options_left_by_solvers(const std::vector<std::pair<std::string, LinearSolverSettings>>& made) {
  std::vector<std::string> viewers;
  PetscOptions options = options_without_viewers(&viewers);
  std::set<std::string> defaults;  // set here as the run sets them: no mistake of the user's if left unread
  bool all_set_up = true;
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // a solver that cannot be set up judges nothing
  for (const auto& [prefix, s] : made) {
    KSP ksp = nullptr;  // destroyed below however far the set-up came
    Mat matrix = nullptr;
    const PetscInt block = prefix == "coupled" ? 3 : 1;  // u, v, p per cell, as the coupled system's
    PetscErrorCode error = make_solver_on(options, prefix, s, &ksp, defaults);
    if (!error) error = KSPSetFromOptions(ksp);
    // Set up on a small diagonal matrix: a factorisation package and AMG read their own options there.
    if (!error) error = MatCreateSeqAIJ(PETSC_COMM_SELF, 2 * block, 2 * block, 1, nullptr, &matrix);
    if (!error) error = MatSetBlockSize(matrix, block);
    for (PetscInt i = 0; !error && i < 2 * block; ++i) error = MatSetValue(matrix, i, i, 1.0, INSERT_VALUES);
    if (!error) error = MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY);
    if (!error) error = MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY);
    if (!error) error = KSPSetOperators(ksp, matrix, matrix);
    if (!error) error = KSPSetUp(ksp);
    if (error) all_set_up = false;
    MatDestroy(&matrix);
    KSPDestroy(&ksp);
  }
  PetscPopErrorHandler();
  std::set<std::string> left;
  if (all_set_up) {
    PetscInt n = 0;
    char **names = nullptr, **values = nullptr;
    PetscOptionsLeftGet(options, &n, &names, &values);
    for (PetscInt k = 0; k < n; ++k)
      if (!defaults.count(names[k])) left.insert(names[k]);
    PetscOptionsLeftRestore(options, &n, &names, &values);
    // A monitor or viewer is not made here. One of a solver (ksp_, pc_) under no made solver's prefix
    // would be read by none; others (-mat_view, -dm_view) are read by the run's matrices and grid.
    for (const auto& name : viewers)
      if ((name.find("ksp_") != std::string::npos || name.find("pc_") != std::string::npos) &&
          std::none_of(made.begin(), made.end(), [&](const auto& m) { return name.rfind(m.first + "_", 0) == 0; }))
        left.insert(name);
  }
  PetscOptionsDestroy(&options);
  return left;
}

std::string unknown_method(const LinearSolverSettings& s) {
  KSP ksp;
  PC pc;
  KSPCreate(PETSC_COMM_SELF, &ksp);
  KSPGetPC(ksp, &pc);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // an unknown name returns an error, quietly
  const PetscErrorCode ksp_error = KSPSetType(ksp, s.ksp_type.c_str());
  const PetscErrorCode pc_error = PCSetType(pc, s.pc_type.c_str());
  PetscPopErrorHandler();
  KSPDestroy(&ksp);
  if (ksp_error) return fmt::format("ksp_type: '{}' is not a Krylov method PETSc knows (e.g. cg, gmres, bcgs, preonly)", s.ksp_type);
  if (pc_error) return fmt::format("pc_type: '{}' is not a preconditioner PETSc knows (e.g. hypre, gamg, bjacobi, lu)", s.pc_type);
  return {};
}


}  // namespace granflow

#include "solver/linear_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/case_error.hpp"
#include "solver/divergence_error.hpp"
#include "solver/out_of_memory_error.hpp"

namespace granflow {

namespace {
// The case file's table of a solver from its options prefix (momentum_x and momentum_y: momentum).
std::string solver_table_name(const std::string& prefix) {
  return prefix.rfind("momentum", 0) == 0 ? "momentum" : prefix;
}

// Ends the run after a PETSc error inside a solve: on one rank as a DivergenceError, on several with
// an abort, since the others may still wait inside the solve for this one, where no collective call
// of ours can meet them.
[[noreturn]] void stop_after_error(KSP ksp, const std::string& problem) {
  MPI_Comm comm;
  PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp), &comm);
  int size;
  MPI_Comm_size(comm, &size);
  if (size == 1) throw DivergenceError(problem);
  fmt::print(stderr, "error: {}\n", problem);
  std::fflush(stderr);
  MPI_Abort(comm, 3);
  std::abort();  // MPI_Abort does not return
}

std::string petsc_error_text(PetscErrorCode error) {
  const char* text = nullptr;
  PetscErrorMessage(error, &text, nullptr);
  return text ? fmt::format("{}, PETSc error {}", text, int(error)) : fmt::format("PETSc error {}", int(error));
}

// Where a tolerance of `ksp`, as PETSc's options may have set it, is outside the case file's range
// ("" if none): PETSc takes any tolerance its options give (-PREFIX_ksp_rtol 2 stops every solve before
// its first iteration, a negative -PREFIX_ksp_max_it at once), so the case file's ranges hold for them too.
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
}  // namespace

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

// What PETSc's options (--petsc, an options file, PETSC_OPTIONS) make of a solver's factorisation that
// PETSc accepts there but cannot carry out: a Cholesky factor of a matrix that is not symmetric (the
// case file refuses it as pc_type), a factorisation package PETSc does not have, or one that does not
// make this factor of this matrix (MUMPS no ILU, a serial package on several ranks). Empty if none.
// case_pc_type: the case file's, whose "lu" makes MUMPS the package unless the options name another.
std::string factorisation_problem(PC pc, const std::string& prefix, const std::string& case_pc_type) {
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
  if (!package && case_pc_type == "lu") package = MATSOLVERMUMPS;  // as the solver will set it (below)
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
  KSP ksp;
  PC pc;
  KSPCreate(PETSC_COMM_SELF, &ksp);
  PetscObjectSetOptions(reinterpret_cast<PetscObject>(ksp), options);
  KSPSetOptionsPrefix(ksp, (prefix + "_").c_str());
  KSPSetType(ksp, s.ksp_type.c_str());
  KSPGetPC(ksp, &pc);
  PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), options);
  PCSetType(pc, s.pc_type.c_str());
  KSPSetTolerances(ksp, s.rtol, s.atol, PETSC_DEFAULT, s.max_iterations);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // what PETSc refuses is told in one line, below
  const PetscErrorCode error = KSPSetFromOptions(ksp);
  PetscPopErrorHandler();
  std::string problem;
  if (error) {
    char* specific = nullptr;
    PetscErrorMessage(error, nullptr, &specific);
    problem = fmt::format("linear solver '{}': PETSc refuses its options: {}", prefix,
                          specific && *specific ? std::string(specific) : petsc_error_text(error));
  } else {
    problem = factorisation_problem(pc, prefix, s.pc_type);
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
    KSP ksp;
    PC pc;
    Mat matrix = nullptr;
    const PetscInt block = prefix == "coupled" ? 3 : 1;  // u, v, p per cell, as the coupled system's
    PetscErrorCode error = KSPCreate(PETSC_COMM_SELF, &ksp);
    if (!error) error = PetscObjectSetOptions(reinterpret_cast<PetscObject>(ksp), options);
    if (!error) error = KSPSetOptionsPrefix(ksp, (prefix + "_").c_str());
    if (!error) error = KSPSetType(ksp, s.ksp_type.c_str());
    if (!error) error = KSPGetPC(ksp, &pc);
    if (!error) error = PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), options);
    if (!error) error = PCSetType(pc, s.pc_type.c_str());
    if (!error && s.pc_type == "lu") {  // the run's default package (LinearSolver), unless the options name another
      const std::string package = "-" + prefix + "_pc_factor_mat_solver_type";
      PetscBool given = PETSC_FALSE;
      PetscOptionsHasName(options, nullptr, package.c_str(), &given);
      if (!given && !PetscOptionsSetValue(options, package.c_str(), "mumps")) defaults.insert(package.substr(1));
    }
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
    // A monitor or viewer is not made here; one under no made solver's prefix would be read by none.
    for (const auto& name : viewers)
      if (std::none_of(made.begin(), made.end(), [&](const auto& m) { return name.rfind(m.first + "_", 0) == 0; }))
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

namespace {
std::set<std::string>& defaults_set() {
  static std::set<std::string> names;
  return names;
}
// An option granflow sets as a default (the user's own option of that name takes precedence).
void set_default_option(const std::string& key, const char* value) {
  PetscBool set;
  PetscOptionsHasName(nullptr, nullptr, key.c_str(), &set);
  if (set) return;
  PetscOptionsSetValue(nullptr, key.c_str(), value);
  defaults_set().insert(key.substr(1));
}
}  // namespace

bool is_default_petsc_option(const std::string& name) { return defaults_set().count(name) > 0; }

LinearSolver::LinearSolver(MPI_Comm comm, const std::string& prefix, const LinearSolverSettings& s)
    : prefix_(prefix), max_reuse_(std::max(1, s.max_reuse)) {
  PetscCallAbort(comm, KSPCreate(comm, ksp_.put()));
  PetscCallAbort(comm, KSPSetOptionsPrefix(ksp_, (prefix + "_").c_str()));
  PetscCallAbort(comm, KSPSetType(ksp_, s.ksp_type.c_str()));
  PC pc;
  PetscCallAbort(comm, KSPGetPC(ksp_, &pc));
  PetscCallAbort(comm, PCSetType(pc, s.pc_type.c_str()));
  PetscCallAbort(comm, KSPSetTolerances(ksp_, s.rtol, s.atol, PETSC_DEFAULT, s.max_iterations));
  PetscCallAbort(comm, KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  if (s.pc_type == "lu")  // a parallel direct solver, unless the user names another
    set_default_option("-" + prefix + "_pc_factor_mat_solver_type", "mumps");
  if (s.pc_type == "hypre") {
    // BoomerAMG with a symmetric smoother, so that it is a valid preconditioner for CG, and the
    // cheaper HMIS coarsening; each is only a default that the user's own options override.
    const std::string p = "-" + prefix + "_pc_hypre_boomeramg_";
    auto set_default = [&](const std::string& key, const char* value) { set_default_option(p + key, value); };
    set_default("relax_type_all", "symmetric-SOR/Jacobi");
    set_default("coarsen_type", "HMIS");
    set_default("interp_type", "ext+i");
    set_default("P_max", "4");
  }
  PetscCallAbort(comm, KSPSetFromOptions(ksp_));
  if (auto problem = tolerance_problem(ksp_, prefix); !problem.empty()) throw CaseError(problem);
  // A direct solve (preonly) takes no initial guess; iterative ones start from the last solution.
  KSPType type;
  KSPGetType(ksp_, &type);
  if (std::string(type) == KSPPREONLY) {
    KSPSetInitialGuessNonzero(ksp_, PETSC_FALSE);
    warn_if_inexact(comm, prefix);
  }
}

// preonly applies the preconditioner once and reports success whatever the residual: a solve only
// with a factorisation. With another preconditioner (jacobi, ilu, hypre) the solve is inexact and
// nothing counts it (its continuity residual leaves the soil volume drifting); said once per solver.
void LinearSolver::warn_if_inexact(MPI_Comm comm, const std::string& prefix) const {
  PC pc;
  KSPGetPC(ksp_, &pc);
  PCType type;
  PCGetType(pc, &type);
  const std::string pc_type = type ? type : "";
  static std::set<std::string> warned;
  if (pc_type == PCLU || pc_type == PCCHOLESKY || pc_type == PCREDUNDANT || !warned.insert(prefix).second) return;
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    fmt::print(stderr,
               "warning: linear solver '{}' applies pc_type = {} once (ksp_type = preonly), which solves only with a "
               "factorisation (lu, cholesky): its solves are inexact and not counted; use pc_type = lu, or a Krylov "
               "method (solver.{}.ksp_type)\n",
               prefix, pc_type, solver_table_name(prefix));
}


namespace {
// A preconditioner that failed (KSP_DIVERGED_PC_FAILED): a factorisation out of memory is said as
// such, and not retried. The reason may be one rank's alone (MUMPS's), so it is reduced over the ranks
// first, the largest (PC_FACTOR_OUTMEMORY over the zero pivots) winning.
void stop_if_out_of_memory(KSP ksp, const std::string& prefix) {
  MPI_Comm comm;
  PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp), &comm);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCFailedReason local = PC_NOERROR;
  PCGetFailedReasonRank(pc, &local);
  int reason = int(local), largest = 0;
  MPI_Allreduce(&reason, &largest, 1, MPI_INT, MPI_MAX, comm);
  if (largest == int(PC_FACTOR_OUTMEMORY))
    throw OutOfMemoryError(fmt::format("linear solver '{}': out of memory in its factorisation (a coarser mesh, a "
                                       "narrower numerics.air_band or more ranks may do)", prefix));
}
}  // namespace

LinearSolver::~LinearSolver() {
  // Quietly: after a failed solve a library's state may be left half made (hypre's vectors), and
  // PETSc would print a second trace while the run is already stopping with its message.
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  reuse_ksp_.reset();
  residual_.reset();
  correction_.reset();
  ksp_.reset();
  PetscPopErrorHandler();
}

int LinearSolver::solve_by_last_factorisation(Vec b, Vec x, int krylov_iterations) {
  MPI_Comm comm;
  PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp_.get()), &comm);
  PC pc;
  Mat a;
  PetscCallAbort(comm, KSPGetPC(ksp_, &pc));
  PetscCallAbort(comm, KSPGetOperators(ksp_, &a, nullptr));
  // Only an exact factorisation of the earlier operator holds its rows (--petsc may have named another).
  PetscBool lu, redundant;  // a redundant solve's own default is LU
  PetscCallAbort(comm, PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCLU, &lu));
  PetscCallAbort(comm, PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCREDUNDANT, &redundant));
  // The last solve() must have factorised (not reused an older step's factorisation).
  if (!(lu || redundant) || !built_ || changes_since_setup_ != 0)
    throw DivergenceError(fmt::format("linear solver '{}': a solve by the last factorisation needs an LU "
                                      "factorisation (pc_type lu or redundant) built by an earlier solve", prefix_));
  if (!residual_) {
    PetscCallAbort(comm, VecDuplicate(b, residual_.put()));
    PetscCallAbort(comm, VecDuplicate(b, correction_.put()));
  }
  // a's new values are not factorised: not by the LU, nor by a redundant solve's inner LU, which on
  // one rank factorises a itself and would see its values changed.
  PC inner = nullptr;
  if (redundant) {
    KSP inner_ksp;
    PetscCallAbort(comm, PCRedundantGetKSP(pc, &inner_ksp));
    PetscCallAbort(comm, KSPGetPC(inner_ksp, &inner));
  }
  auto reuse = [&](PetscBool flag) {
    PetscCallAbort(comm, PCSetReusePreconditioner(pc, flag));
    if (inner) PetscCallAbort(comm, PCSetReusePreconditioner(inner, flag));
  };
  reuse(PETSC_TRUE);
  PetscCallAbort(comm, MatMult(a, x, residual_));
  PetscCallAbort(comm, VecAYPX(residual_, -1.0, b));
  PetscCallAbort(comm, PCApply(pc, residual_, correction_));
  PetscCallAbort(comm, VecAXPY(x, 1.0, correction_));
  if (!reuse_ksp_) {
    // Flexible GMRES keeps the preconditioned vectors: no application of P after its last iteration.
    PetscCallAbort(comm, KSPCreate(comm, reuse_ksp_.put()));
    PetscCallAbort(comm, KSPSetType(reuse_ksp_, KSPFGMRES));
    // Its own prefix, for PETSc's monitors (-coupled_later_ksp_monitor_true_residual), set before the
    // shared preconditioner is attached, whose options stay the first solve's own.
    PetscCallAbort(comm, KSPSetOptionsPrefix(reuse_ksp_, (prefix_ + "_later_").c_str()));
    PetscCallAbort(comm, KSPSetPC(reuse_ksp_, pc));
    PetscCallAbort(comm, KSPSetSkipPCSetFromOptions(reuse_ksp_, PETSC_TRUE));
    PetscCallAbort(comm, KSPSetPCSide(reuse_ksp_, PC_RIGHT));
    PetscCallAbort(comm, KSPSetInitialGuessNonzero(reuse_ksp_, PETSC_TRUE));
    PetscCallAbort(comm, KSPSetFromOptions(reuse_ksp_));
  }
  PetscCallAbort(comm, KSPSetOperators(reuse_ksp_, a, a));
  PetscCallAbort(comm, KSPSetReusePreconditioner(reuse_ksp_, PETSC_TRUE));
  // A fixed number of iterations: the outer iterations, not this solve, converge the step.
  PetscCallAbort(comm, KSPSetTolerances(reuse_ksp_, 1e-14, 0.0, PETSC_DEFAULT, krylov_iterations));
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode error = KSPSolve(reuse_ksp_, b, x);
  PetscPopErrorHandler();
  reuse(PETSC_FALSE);  // solve() decides anew
  if (error)
    stop_after_error(reuse_ksp_, fmt::format("linear solver '{}' failed in a solve by its last factorisation: {}",
                                             prefix_, petsc_error_text(error)));
  // Stopping at the iteration count is the plan; a breakdown or a NaN is not (the same on every rank).
  KSPConvergedReason reason;
  KSPGetConvergedReason(reuse_ksp_, &reason);
  if (reason == KSP_DIVERGED_PC_FAILED) stop_if_out_of_memory(reuse_ksp_, prefix_);
  if (reason < 0 && reason != KSP_DIVERGED_ITS)
    throw LinearSolveFailure(fmt::format("linear solver '{}' failed in a solve by its last factorisation: {}",
                                         prefix_, KSPConvergedReasons[reason]));
  PetscInt its;
  KSPGetIterationNumber(reuse_ksp_, &its);
  return 1 + int(its);
}

void LinearSolver::set_operator(Mat a) {
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetOperators(ksp_, a, a));
  ++changes_since_setup_;
}

int LinearSolver::solve(Vec b, Vec x) {
  // Solves with an unchanged operator keep the preconditioner anyway; only changes count.
  const bool rebuild = !built_ || (changes_since_setup_ > 0 && (changes_since_setup_ >= max_reuse_ ||
                                   last_iterations_ > 2 * std::max(iterations_after_setup_, 2)));
  KSPSetReusePreconditioner(ksp_, rebuild ? PETSC_FALSE : PETSC_TRUE);
  // A failure inside the solve (an external library's, a preconditioner that cannot be built) ends
  // the run with one message instead of PETSc's error trace: on one rank as a DivergenceError, on
  // several with an abort.
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode error = KSPSolve(ksp_, b, x);
  PetscPopErrorHandler();
  if (error)
    stop_after_error(ksp_, fmt::format("linear solver '{}' failed: {}; another solver.{}.pc_type may do", prefix_,
                                       petsc_error_text(error), solver_table_name(prefix_)));
  KSPConvergedReason reason;
  PetscInt its;
  KSPGetConvergedReason(ksp_, &reason);
  KSPGetIterationNumber(ksp_, &its);
  if (rebuild) {
    built_ = true;
    changes_since_setup_ = 0;
    iterations_after_setup_ = int(its);
  }
  last_iterations_ = int(its);
  if (reason == KSP_DIVERGED_ITS && solves_at_limit_++ == 0) {
    MPI_Comm comm;
    PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp_.get()), &comm);
    int rank;
    MPI_Comm_rank(comm, &rank);
    PetscInt max_iterations;
    KSPGetTolerances(ksp_, nullptr, nullptr, nullptr, &max_iterations);
    if (rank == 0)
      fmt::print(stderr,
                 "warning: linear solver '{}' stopped at solver.{}.max_iterations = {} before its rtol; the run goes "
                 "on and counts such solves in its last line\n",
                 prefix_, solver_table_name(prefix_), max_iterations);
  }
  // The converged reason is the same on every rank, so all stop together, as for a diverged flow.
  if (reason == KSP_DIVERGED_PC_FAILED) stop_if_out_of_memory(ksp_, prefix_);
  if (reason < 0 && reason != KSP_DIVERGED_ITS) {
    built_ = false;  // a step taken again builds its preconditioner anew
    throw LinearSolveFailure(fmt::format("linear solver '{}' failed: {}", prefix_, KSPConvergedReasons[reason]));
  }
  return int(its);
}

}  // namespace granflow

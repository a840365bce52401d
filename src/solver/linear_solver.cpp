#include "solver/linear_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <utility>
#include <vector>
#include <stdexcept>

#include "io/case_error.hpp"
#include "solver/divergence_error.hpp"
#include "solver/solver_options_check.hpp"
#include "solver/out_of_memory_error.hpp"

namespace granflow {

namespace {
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
}  // namespace


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

LinearSolver::LinearSolver(MPI_Comm comm, const std::string& prefix, const LinearSolverSettings& s,
                           int mesh_dimension)
    : prefix_(prefix), max_reuse_(std::max(1, s.max_reuse)) {
  PetscCallAbort(comm, KSPCreate(comm, ksp_.put()));
  PetscCallAbort(comm, KSPSetOptionsPrefix(ksp_, (prefix + "_").c_str()));
  PetscCallAbort(comm, KSPSetType(ksp_, s.ksp_type.c_str()));
  PC pc;
  PetscCallAbort(comm, KSPGetPC(ksp_, &pc));
  PetscCallAbort(comm, PCSetType(pc, s.pc_type.c_str()));
  PetscCallAbort(comm, KSPSetTolerances(ksp_, s.rtol, s.atol, PETSC_DEFAULT, s.max_iterations));
  PetscCallAbort(comm, KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  if (const char* package = default_factorisation_package(s))  // unless the user names another
    set_default_option("-" + prefix + "_pc_factor_mat_solver_type", package);
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
  // On a mesh of layers, hypre's advice for 3D problems: a strong threshold of 0.5 and one level of
  // aggressive coarsening (the quarter column under the projection: 0.7 of the wall time; docs/
  // benchmarks.md). Set for this solver's reading only, and cleared after it, so that a planar solver
  // made later in the same process reads none of them (the 2D defaults above are the same for both).
  std::vector<std::string> read_once;
  if (s.pc_type == "hypre" && mesh_dimension == 3)
    for (const auto& [key, value] : {std::pair{"strong_threshold", "0.5"}, std::pair{"agg_nl", "1"}}) {
      const std::string name = "-" + prefix + "_pc_hypre_boomeramg_" + key;
      PetscBool given;
      PetscCallAbort(comm, PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given));
      if (given) continue;
      PetscCallAbort(comm, PetscOptionsSetValue(nullptr, name.c_str(), value));
      read_once.push_back(name);
    }
  PetscCallAbort(comm, KSPSetFromOptions(ksp_));
  for (const auto& name : read_once) PetscCallAbort(comm, PetscOptionsClearValue(nullptr, name.c_str()));
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

#pragma once
// A PETSc KSP with defaults from the case file, overridable from PETSc's own command-line options
// under a prefix (e.g. -pressure_ksp_type cg -pressure_pc_type gamg).
#include <petscksp.h>

#include <string>

#include "mesh/petsc_handle.hpp"

namespace granflow {

struct LinearSolverSettings {
  std::string ksp_type = "bcgs";
  std::string pc_type = "hypre";
  double rtol = 1e-8;
  double atol = 1e-14;
  int max_iterations = 1000;
  // Keep the preconditioner over up to this many changes of the operator (1: rebuild at every
  // change); it is rebuilt earlier when a solve needs more than twice the iterations it took right
  // after the last rebuild. AMG set-up is most of the cost of a solve.
  int max_reuse = 1;
};

// The factorisation package a solver of these settings takes unless PETSc's options name another
// (-PREFIX_pc_factor_mat_solver_type): MUMPS, a parallel one, for pc_type = "lu"; none (nullptr) otherwise.
inline const char* default_factorisation_package(const LinearSolverSettings& settings) {
  return settings.pc_type == "lu" ? "mumps" : nullptr;
}

// Whether granflow itself set the PETSc option `name` (without its '-') as a solver's default:
// the user's --petsc may make another preconditioner read none of them, which is no mistake.
bool is_default_petsc_option(const std::string& name);

class LinearSolver {
 public:
  // mesh_dimension: 3 on a mesh of layers, whose BoomerAMG takes hypre's settings for 3D problems
  // (a stronger threshold, one level of aggressive coarsening) unless the user's options say otherwise.
  LinearSolver(MPI_Comm comm, const std::string& prefix, const LinearSolverSettings& settings,
               int mesh_dimension = 2);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Call after the matrix values changed; the preconditioner is rebuilt at the next solve.
  void set_operator(Mat a);
  // Solves a x = b from the initial guess in x; returns the iteration count. Throws on divergence.
  int solve(Vec b, Vec x);
  // Solves a x = b, a being the operator of the last solve() with new values, by that solve's
  // factorisation P: one Richardson correction x += P^-1 (b - a x), then up to `krylov_iterations`
  // of FGMRES preconditioned by P on the right. The rows where a equals P (a saddle point's
  // constraint rows) hold exactly after the correction, and every Krylov update keeps them so: the
  // Krylov vectors (a P^-1)^k r are zero in those rows when r is. Returns P's applications.
  int solve_by_last_factorisation(Vec b, Vec x, int krylov_iterations);
  // Whether solve() has built its preconditioner since it was made or last told to rebuild.
  bool has_preconditioner() const { return built_; }
  // The next solve builds its preconditioner anew, as a solver made afresh would: a run restarted
  // from a checkpoint makes its solvers afresh, so the run that wrote it rebuilds there too.
  void rebuild_at_next_solve() { built_ = false; }
  KSP ksp() const { return ksp_; }
  const std::string& name() const { return prefix_; }
  // Solves that stopped at max_iterations before rtol (accepted: the outer iterations may converge
  // the rest, and a reused factorisation may be asked for a few iterations only; but the face
  // fluxes then carry the residual, and the soil volume with them).
  long solves_at_iteration_limit() const { return solves_at_limit_; }
  // A solver that takes over from others (a new pattern) goes on with their count, and their warning.
  void continue_count(long solves_at_limit_before) { solves_at_limit_ = solves_at_limit_before; }

 private:
  // Warns (once per solver, rank 0) where preonly applies a preconditioner that does not factorise.
  void warn_if_inexact(MPI_Comm comm, const std::string& prefix) const;
  OwnedKsp ksp_;
  OwnedKsp reuse_ksp_;  // FGMRES on ksp_'s preconditioner (solve_by_last_factorisation)
  OwnedVec residual_, correction_;
  std::string prefix_;
  int max_reuse_ = 1;
  bool built_ = false;
  int changes_since_setup_ = 0;  // operator changes since the preconditioner was built
  int iterations_after_setup_ = 0;
  int last_iterations_ = 0;
  long solves_at_limit_ = 0;
};

}  // namespace granflow

#pragma once
// A PETSc KSP with defaults from the case file, overridable from PETSc's own command-line options
// under a prefix (e.g. -pressure_ksp_type cg -pressure_pc_type gamg).
#include <petscksp.h>

#include <string>

namespace granflow {

struct LinearSolverSettings {
  std::string ksp_type = "bcgs";
  std::string pc_type = "hypre";
  double rtol = 1e-8;
  double atol = 1e-14;
  int max_iterations = 1000;
};

class LinearSolver {
 public:
  LinearSolver(MPI_Comm comm, const std::string& prefix, const LinearSolverSettings& settings);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Call after the matrix values changed; the preconditioner is rebuilt at the next solve.
  void set_operator(Mat a);
  // Solves a x = b from the initial guess in x; returns the iteration count. Throws on divergence.
  int solve(Vec b, Vec x);
  KSP ksp() const { return ksp_; }
  const std::string& name() const { return prefix_; }

 private:
  KSP ksp_ = nullptr;
  std::string prefix_;
};

}  // namespace granflow

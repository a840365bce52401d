// LinearSolver::solve_by_last_factorisation on a small saddle point [K B^T; B 0]: after K changes
// (its viscosities by up to a decade each way, as between two outer iterations), a solve by the
// old factorisation must meet the constraint rows B u = g exactly, whatever its Krylov iterations.
#include <gtest/gtest.h>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../../lu_factorisations.hpp"
#include "solver/divergence_error.hpp"
#include "solver/linear_solver.hpp"

namespace granflow {
namespace {

constexpr int velocities = 40, constraints = 10, unknowns = velocities + constraints;

// K from viscosities mu (a diffusion chain with a convection-like lower band), B fixed.
void fill(Mat a, const std::vector<double>& mu) {
  MatZeroEntries(a);
  for (int i = 0; i < velocities; ++i) {
    const double left = mu[i], right = mu[i + 1];
    MatSetValue(a, i, i, left + right + 1.0, INSERT_VALUES);
    if (i > 0) MatSetValue(a, i, i - 1, -left - 0.3, INSERT_VALUES);
    if (i + 1 < velocities) MatSetValue(a, i, i + 1, -right, INSERT_VALUES);
  }
  for (int c = 0; c < constraints; ++c)
    for (int k = 0; k < 4; ++k) {
      const int i = 4 * c + k;
      const double b = (k % 2 ? -1.0 : 1.0) * (1.0 + 0.25 * k);
      MatSetValue(a, velocities + c, i, b, INSERT_VALUES);  // B
      MatSetValue(a, i, velocities + c, b, INSERT_VALUES);  // B^T
    }
  MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY);
}

Vec rhs(double scale) {
  Vec b;
  VecCreateSeq(PETSC_COMM_SELF, unknowns, &b);
  for (int i = 0; i < unknowns; ++i) VecSetValue(b, i, scale * std::sin(0.7 * i + 0.2), INSERT_VALUES);
  VecAssemblyBegin(b);
  VecAssemblyEnd(b);
  return b;
}

// Largest |(a x - b)_i| over the constraint rows, and the 2-norm over all rows.
std::pair<double, double> residuals(Mat a, Vec x, Vec b) {
  Vec r;
  VecDuplicate(b, &r);
  MatMult(a, x, r);
  VecAYPX(r, -1.0, b);
  const double* v;
  VecGetArrayRead(r, &v);
  double constraint = 0.0, all = 0.0;
  for (int i = 0; i < unknowns; ++i) {
    if (i >= velocities) constraint = std::max(constraint, std::abs(v[i]));
    all += v[i] * v[i];
  }
  VecRestoreArrayRead(r, &v);
  VecDestroy(&r);
  return {constraint, std::sqrt(all)};
}

struct Saddle {
  Mat a;
  std::vector<double> first_mu, later_mu;
  Saddle() : first_mu(velocities + 1), later_mu(velocities + 1) {
    MatCreateSeqAIJ(PETSC_COMM_SELF, unknowns, unknowns, 8, nullptr, &a);
    MatSetOption(a, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> decade(-1.0, 1.0);
    for (int i = 0; i <= velocities; ++i) {
      first_mu[i] = std::pow(10.0, 3.0 * (i % 7) / 6.0);  // 1 to 1000
      later_mu[i] = first_mu[i] * std::pow(10.0, decade(random));
    }
  }
  ~Saddle() { MatDestroy(&a); }
};

LinearSolverSettings direct() { return {"preonly", "lu", 1e-12, 1e-14, 1}; }

// Solves with the first operator, then refills it with the later viscosities and solves the later
// right-hand side by the first factorisation with `krylov` iterations; returns the residuals.
std::pair<double, double> later_solve(int krylov, Vec* solution = nullptr) {
  Saddle s;
  LinearSolver solver(PETSC_COMM_SELF, "unit_reuse", direct());
  fill(s.a, s.first_mu);
  Vec b = rhs(1.0), x;
  VecDuplicate(b, &x);
  VecSet(x, 0.0);
  solver.set_operator(s.a);
  solver.solve(b, x);
  fill(s.a, s.later_mu);
  Vec later = rhs(3.0);  // the constraint rows' right-hand side changes too
  const int applications = solver.solve_by_last_factorisation(later, x, krylov);
  EXPECT_LE(applications, 1 + krylov);  // fewer once it has converged
  if (krylov <= 5) EXPECT_EQ(applications, 1 + krylov);
  const auto r = residuals(s.a, x, later);
  if (solution) VecCopy(x, *solution);
  VecDestroy(&b);
  VecDestroy(&later);
  VecDestroy(&x);
  return r;
}

TEST(LinearSolver, SolveByLastFactorisationHoldsTheConstraintRowsExactly) {
  double richardson_residual = 0.0;
  for (int krylov : {0, 1, 2, 5}) {
    const auto [constraint, all] = later_solve(krylov);
    EXPECT_LT(constraint, 1e-13) << krylov << " Krylov iterations";
    if (krylov == 0) richardson_residual = all;
    else EXPECT_LT(all, richardson_residual) << krylov << " Krylov iterations";
    std::printf("Krylov iterations %d: constraint residual %.2e, residual %.3e\n", krylov, constraint, all);
  }
}

TEST(LinearSolver, SolveByLastFactorisationConvergesToTheNewOperatorsSolution) {
  Vec reused, exact;
  VecCreateSeq(PETSC_COMM_SELF, unknowns, &reused);
  VecDuplicate(reused, &exact);
  later_solve(unknowns, &reused);
  {
    Saddle s;
    fill(s.a, s.later_mu);
    LinearSolver solver(PETSC_COMM_SELF, "unit_exact", direct());
    Vec later = rhs(3.0);
    VecSet(exact, 0.0);
    solver.set_operator(s.a);
    solver.solve(later, exact);
    VecDestroy(&later);
  }
  double difference, size;
  VecNorm(exact, NORM_INFINITY, &size);
  VecAXPY(reused, -1.0, exact);
  VecNorm(reused, NORM_INFINITY, &difference);
  EXPECT_LT(difference, 1e-9 * size);
  VecDestroy(&reused);
  VecDestroy(&exact);
}

// The later solve factorises nothing, with LU and with a redundant solve's LU (on one rank the
// latter factorises the operator itself, whose values have changed); the next solve() does.
TEST(LinearSolver, SolveByLastFactorisationFactorisesNothing) {
  PetscOptionsSetValue(nullptr, "-unit_redundant_redundant_pc_factor_mat_solver_type", "mumps");
  for (const char* pc_type : {"lu", "redundant"}) {
    Saddle s;
    LinearSolverSettings settings = direct();
    settings.pc_type = pc_type;
    LinearSolver solver(PETSC_COMM_SELF, std::string("unit_") + pc_type, settings);
    fill(s.a, s.first_mu);
    Vec b = rhs(1.0), x;
    VecDuplicate(b, &x);
    VecSet(x, 0.0);
    solver.set_operator(s.a);
    const int before = test::lu_factorisations();
    solver.solve(b, x);
    EXPECT_EQ(test::lu_factorisations(), before + 1) << pc_type;
    fill(s.a, s.later_mu);
    solver.solve_by_last_factorisation(b, x, 2);
    EXPECT_EQ(test::lu_factorisations(), before + 1) << pc_type << ": the later solve factorised";
    const auto [constraint, all] = residuals(s.a, x, b);
    EXPECT_LT(constraint, 1e-13) << pc_type;
    solver.set_operator(s.a);
    solver.solve(b, x);
    EXPECT_EQ(test::lu_factorisations(), before + 2) << pc_type << ": solve() did not factorise the new values";
    EXPECT_LT(residuals(s.a, x, b).second, 1e-10 * all + 1e-12) << pc_type;
    VecDestroy(&b);
    VecDestroy(&x);
  }
}

TEST(LinearSolver, SolveByLastFactorisationNeedsOne) {
  Saddle s;
  fill(s.a, s.first_mu);
  Vec b = rhs(1.0), x;
  VecDuplicate(b, &x);
  VecSet(x, 0.0);
  LinearSolver solver(PETSC_COMM_SELF, "unit_none", direct());
  solver.set_operator(s.a);
  EXPECT_THROW(solver.solve_by_last_factorisation(b, x, 2), DivergenceError);  // nothing factorised yet
  VecDestroy(&b);
  VecDestroy(&x);
}

// BoomerAMG on a mesh of layers takes hypre's settings for 3D problems (strong threshold 0.5, one
// level of aggressive coarsening), read by that solver alone: a planar solver of the same prefix made
// after it keeps hypre's 0.25 and none, and the user's own option overrides the 3D default.
TEST(LinearSolver, BoomerAmgOnAMeshOfLayersTakesTheSettingsFor3dProblems) {
  auto view_of = [](const LinearSolver& solver) {  // what PCView writes (hypre's settings in ASCII only)
    PC pc;
    KSPGetPC(solver.ksp(), &pc);
    const std::string path = (std::filesystem::temp_directory_path() / "granflow_unit_amg_view.txt").string();
    PetscViewer viewer;
    PetscViewerASCIIOpen(PETSC_COMM_SELF, path.c_str(), &viewer);
    PCView(pc, viewer);
    PetscViewerDestroy(&viewer);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::filesystem::remove(path);
    return text.str();
  };
  LinearSolverSettings amg;
  amg.ksp_type = "cg";
  amg.pc_type = "hypre";
  const std::string layers = view_of(LinearSolver(PETSC_COMM_SELF, "unit_amg", amg, 3));
  EXPECT_NE(layers.find("Threshold for strong coupling 0.5"), std::string::npos) << layers;
  EXPECT_NE(layers.find("Number of levels of aggressive coarsening 1"), std::string::npos) << layers;
  const std::string planar = view_of(LinearSolver(PETSC_COMM_SELF, "unit_amg", amg, 2));
  EXPECT_NE(planar.find("Threshold for strong coupling 0.25"), std::string::npos) << planar;
  EXPECT_NE(planar.find("Number of levels of aggressive coarsening 0"), std::string::npos) << planar;
  PetscOptionsSetValue(nullptr, "-unit_amg_pc_hypre_boomeramg_strong_threshold", "0.7");
  const std::string given = view_of(LinearSolver(PETSC_COMM_SELF, "unit_amg", amg, 3));
  PetscBool kept = PETSC_FALSE;  // the user's option stays for the solvers made after
  PetscOptionsHasName(nullptr, nullptr, "-unit_amg_pc_hypre_boomeramg_strong_threshold", &kept);
  PetscOptionsClearValue(nullptr, "-unit_amg_pc_hypre_boomeramg_strong_threshold");
  EXPECT_NE(given.find("Threshold for strong coupling 0.7"), std::string::npos) << given;
  EXPECT_NE(given.find("Number of levels of aggressive coarsening 1"), std::string::npos) << given;
  EXPECT_TRUE(kept);
}

}  // namespace
}  // namespace granflow

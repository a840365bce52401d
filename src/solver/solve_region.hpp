#pragma once
// The cells the coupled velocity-pressure solve covers when numerics.air_band > 0: the soil and a band
// of air around it. The air beyond is held at rest at its hydrostatic pressure and enters the solve
// as known neighbour values, like an atmosphere. The soil feels the air only through pressures of
// order rho_air U^2 (about 1 Pa against the soil's kPa), so the pile is the same, and the direct
// factorisation covers about a quarter of the domain instead of all of it (docs/method.md, "Air band").
//
// The cells are a 0/1 mask field (part of the flow state, so a retried step and a restart see the
// same region). The region's system is assembled directly in its own numbering: a column outside
// the region moves to the right-hand side with its known value. Numbering, matrix and solver are
// made anew only when the mask changes; between changes the matrix is refilled in place and the
// factorisation's analysis is reused.
#include <petscksp.h>

#include <memory>
#include <vector>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "solver/linear_solver.hpp"

namespace granflow {

class SolveRegion {
 public:
  SolveRegion(const Grid& grid, const LinearSolverSettings& solver);
  ~SolveRegion();
  SolveRegion(const SolveRegion&) = delete;
  SolveRegion& operator=(const SolveRegion&) = delete;

  // 1 in the cells the solve covers, 0 outside.
  Field& cells() { return cells_; }
  const Field& cells() const { return cells_; }
  // Whether every cell where `needed` is non-zero lies in the region (on every rank).
  bool covers(const Field& needed) const;
  // Whether the region holds any cell (on any rank): none before the first is laid, also where a
  // step taken again or a restart restored the state of then.
  bool laid() const;
  // The region becomes the cells where `wanted` is non-zero, less the blocked ones.
  void assign(const Field& wanted);
  // Cells no region holds: an obstacle's (mesh/obstacles.hpp), whose local mask is kept by the caller.
  void set_blocked(const Field* mask) { blocked_ = mask; }

  // Numbers the region's cells anew (and makes a new matrix and solver) if the mask changed since
  // the last call; returns the region's cells over all ranks. Call before filling the rows.
  long prepare();
  // Cells in the region over all ranks, after the last prepare().
  long cell_count() const { return cell_count_; }
  // See LinearSolver::rebuild_at_next_solve.
  void rebuild_at_next_solve() {
    if (solver_) solver_->rebuild_at_next_solve();
  }
  // Solves that stopped at their max_iterations (LinearSolver), over every pattern so far.
  long solves_at_iteration_limit() const { return solver_ ? solver_->solves_at_iteration_limit() : solves_at_limit_before_; }

  // Fills the region's rows, one (cell, unknown) at a time, while it lives; the matrix is
  // assembled when it goes. Columns are given as grid stencils; those outside the region are
  // moved to the right-hand side with the value `outside(i, j, k, unknown)`.
  class RowWriter {
   public:
    explicit RowWriter(SolveRegion& region);
    ~RowWriter();
    RowWriter(const RowWriter&) = delete;
    RowWriter& operator=(const RowWriter&) = delete;

    bool inside(int i, int j, int k) const { return index_[k][j][i] >= 0.0; }
    template <class Outside>
    void set(int i, int j, int k, int unknown, int n, const MatStencil* cols, const double* vals, double rhs,
             Outside&& outside) {
      constexpr int most_columns = 16;
      PetscCheckAbort(n <= most_columns, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                      "a coupled row of %d columns (at most %d)", n, most_columns);
      const int per_cell = region_.unknowns_per_cell_;
      PetscInt region_cols[most_columns];
      double region_vals[most_columns];
      int m = 0;
      for (int e = 0; e < n; ++e) {
        const double c = index_[cols[e].k][cols[e].j][cols[e].i];
        if (c >= 0.0) {
          region_cols[m] = per_cell * PetscInt(c) + cols[e].c;
          region_vals[m++] = vals[e];
        } else {
          rhs -= vals[e] * outside(cols[e].i, cols[e].j, cols[e].k, cols[e].c);
        }
      }
      const PetscInt row = per_cell * PetscInt(index_[k][j][i]) + unknown;
      PetscCallAbort(PETSC_COMM_SELF,
                     MatSetValues(region_.matrix_, 1, &row, m, region_cols, region_vals, INSERT_VALUES));
      rhs_[row - region_.first_row_] = rhs;
    }

   private:
    SolveRegion& region_;
    ConstFieldArray index_array_;
    VolumeView index_;
    PetscScalar* rhs_ = nullptr;
  };

  // Solves the region's system (after a RowWriter filled it) and writes the region's unknowns into
  // `x`, a (u, v, p) or (u, v, w, p) vector of the whole grid laid out as the grid; the other entries of x are left
  // as they are. `x` also gives the initial guess of an iterative solver. Returns the iterations.
  int solve(Vec x);
  // The same by the factorisation of the last solve() (LinearSolver::solve_by_last_factorisation).
  int solve_by_last_factorisation(Vec x, int krylov_iterations);
  // Whether the last solve()'s factorisation is there for that: not after a new pattern (prepare()).
  bool has_factorisation() const { return solver_ && solver_->has_preconditioner(); }

 private:
  void copy_solution(Vec x, bool into_region);
  const Grid& grid_;
  const int unknowns_per_cell_;  // the velocity's components and the pressure
  LinearSolverSettings solver_settings_;
  Field cells_;
  Field index_;                 // region number of each cell (-1 outside), with ghosts
  const Field* blocked_ = nullptr;
  std::vector<int> owned_;      // owned region cells as ((k - zs) ym + (j - ys)) xm + (i - xs), of the last prepare()
  std::vector<int> candidate_;  // the same for the present mask, kept to reuse its memory
  bool numbered_ = false;       // prepare() has numbered a region (an empty one has no matrix)
  long cell_count_ = 0;
  PetscInt first_row_ = 0;      // the first of this rank's rows in the region's numbering
  OwnedMat matrix_;
  OwnedVec rhs_, solution_;
  std::unique_ptr<LinearSolver> solver_;
  long solves_at_limit_before_ = 0;  // of the solvers of earlier patterns
};

}  // namespace granflow

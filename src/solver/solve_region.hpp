#pragma once
// The cells the coupled velocity-pressure solve covers when numerics.air_band > 0: the soil and a band
// of air around it. The air beyond is held at rest at its hydrostatic pressure and enters the solve
// as known neighbour values, like an atmosphere. The soil feels the air only through pressures of
// order rho_air U^2 (about 1 Pa against the soil's kPa), so the pile is the same, and the direct
// factorisation covers a fifth of the domain instead of all of it (docs/method.md, "Air band").
//
// The cells are a 0/1 mask field (part of the flow state, so a retried step and a restart see the
// same region). The rows of the coupled system they hold, the submatrix and its solver are rebuilt
// only when the mask changes; between changes the factorisation's analysis is reused.
#include <petscksp.h>

#include <memory>
#include <vector>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "solver/linear_solver.hpp"

namespace granflow {

class SolveRegion {
 public:
  SolveRegion(const Grid& grid, DM coupled_dm, const LinearSolverSettings& solver);
  ~SolveRegion();
  SolveRegion(const SolveRegion&) = delete;
  SolveRegion& operator=(const SolveRegion&) = delete;

  // 1 in the cells the solve covers, 0 outside.
  Field& cells() { return cells_; }
  // Whether every cell where `needed` is non-zero lies in the region (on every rank).
  bool covers(const Field& needed) const;
  // The region becomes the cells where `wanted` is non-zero.
  void assign(const Field& wanted);
  // Solves the region's rows of a x = b for the region's unknowns of x; the other entries of x
  // hold the known outside values on entry and are left as they are. Returns the iterations.
  int solve(Mat a, Vec b, Vec x);
  // Cells in the region over all ranks, after the last solve.
  long cell_count() const { return cell_count_; }

 private:
  const Grid& grid_;
  DM coupled_dm_;
  LinearSolverSettings solver_settings_;
  Field cells_;
  std::vector<PetscInt> rows_;  // owned rows of the coupled system in the region, of the last solve
  long cell_count_ = 0;
  IS rows_is_ = nullptr;
  Mat matrix_ = nullptr;
  Vec residual_ = nullptr;  // b - A x_outside
  std::unique_ptr<LinearSolver> solver_;
};

}  // namespace granflow

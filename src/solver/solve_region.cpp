#include "solver/solve_region.hpp"

namespace granflow {

namespace {
constexpr int unknowns_per_cell = 3;  // u, v, p
}  // namespace

SolveRegion::SolveRegion(const Grid& grid, DM coupled_dm, const LinearSolverSettings& solver)
    : grid_(grid), coupled_dm_(coupled_dm), solver_settings_(solver), cells_(grid) {
  cells_.set(0.0);  // empty until assigned: the first step lays the band
}

SolveRegion::~SolveRegion() {
  solver_.reset();
  MatDestroy(&matrix_);
  ISDestroy(&rows_is_);
  VecDestroy(&residual_);
}

bool SolveRegion::covers(const Field& needed) const {
  const auto& b = grid_.owned();
  ConstFieldArray in(grid_.field_dm(), needed.global()), mine(grid_.field_dm(), cells_.global());
  int missing = 0;
  for (int j = b.ys; j < b.ye() && !missing; ++j)
    for (int i = b.xs; i < b.xe(); ++i)
      if (in[j][i] != 0.0 && mine[j][i] == 0.0) {
        missing = 1;
        break;
      }
  int any = 0;
  MPI_Allreduce(&missing, &any, 1, MPI_INT, MPI_MAX, grid_.comm());
  return any == 0;
}

void SolveRegion::assign(const Field& wanted) {
  const auto& b = grid_.owned();
  {
    ConstFieldArray in(grid_.field_dm(), wanted.global());
    FieldArray mine(grid_.field_dm(), cells_.global());
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) mine[j][i] = in[j][i] != 0.0 ? 1.0 : 0.0;
  }
  cells_.scatter_to_local();
}

int SolveRegion::solve(Mat a, Vec b, Vec x) {
  const MPI_Comm comm = grid_.comm();
  const auto& box = grid_.owned();
  PetscInt first_row;
  PetscCallAbort(comm, VecGetOwnershipRange(b, &first_row, nullptr));
  std::vector<PetscInt> rows;
  {
    ConstFieldArray mine(grid_.field_dm(), cells_.global());
    for (int j = box.ys; j < box.ye(); ++j)
      for (int i = box.xs; i < box.xe(); ++i)
        if (mine[j][i] != 0.0) {
          const PetscInt row = first_row + unknowns_per_cell * (PetscInt(j - box.ys) * box.xm + (i - box.xs));
          for (int k = 0; k < unknowns_per_cell; ++k) rows.push_back(row + k);
        }
  }
  int changed = (!matrix_ || rows != rows_) ? 1 : 0, any_changed = 0;
  MPI_Allreduce(&changed, &any_changed, 1, MPI_INT, MPI_MAX, comm);
  if (any_changed) {
    solver_.reset();
    MatDestroy(&matrix_);
    ISDestroy(&rows_is_);
    rows_ = std::move(rows);
    long local = long(rows_.size()) / unknowns_per_cell;
    MPI_Allreduce(&local, &cell_count_, 1, MPI_LONG, MPI_SUM, comm);
    if (cell_count_ == 0) return 0;  // no soil left: nothing but air at rest
    PetscCallAbort(comm, ISCreateGeneral(comm, PetscInt(rows_.size()), rows_.data(), PETSC_COPY_VALUES, &rows_is_));
    PetscCallAbort(comm, MatCreateSubMatrix(a, rows_is_, rows_is_, MAT_INITIAL_MATRIX, &matrix_));
    // A new pattern needs a new factorisation analysis; a fresh solver also takes the new sizes.
    solver_ = std::make_unique<LinearSolver>(comm, "coupled", solver_settings_);
  } else {
    if (cell_count_ == 0) return 0;
    PetscCallAbort(comm, MatCreateSubMatrix(a, rows_is_, rows_is_, MAT_REUSE_MATRIX, &matrix_));
  }
  // Right-hand side of the region's rows: b - A x with x zero in the region and the known values outside.
  if (!residual_) PetscCallAbort(comm, VecDuplicate(b, &residual_));
  PetscCallAbort(comm, VecISSet(x, rows_is_, 0.0));
  PetscCallAbort(comm, MatMult(a, x, residual_));
  PetscCallAbort(comm, VecAYPX(residual_, -1.0, b));
  Vec region_rhs, region_x;
  PetscCallAbort(comm, VecGetSubVector(residual_, rows_is_, &region_rhs));
  PetscCallAbort(comm, VecGetSubVector(x, rows_is_, &region_x));
  solver_->set_operator(matrix_);
  const int iterations = solver_->solve(region_rhs, region_x);
  PetscCallAbort(comm, VecRestoreSubVector(x, rows_is_, &region_x));  // copies the solution back into x
  PetscCallAbort(comm, VecRestoreSubVector(residual_, rows_is_, &region_rhs));
  return iterations;
}

}  // namespace granflow

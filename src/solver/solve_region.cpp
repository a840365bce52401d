#include "solver/solve_region.hpp"

#include "mesh/cell_unknowns.hpp"
#include "mesh/obstacles.hpp"

namespace granflow {

namespace {
// Entries of a region cell's rows: its continuity row has the most, two per face and one per unknown
// of its own (12 on a planar mesh, 16 on a mesh of layers).
PetscInt entries_per_row(int dimension) { return 4 * dimension + 4; }

// The owned cell at offset `at` = ((k - zs) ym + (j - ys)) xm + (i - xs) of the rank's block.
struct OwnedCell {
  int i, j, k;
};
OwnedCell owned_cell(const CellBox& b, int at) {
  return {b.xs + at % b.xm, b.ys + (at / b.xm) % b.ym, b.zs + at / (b.xm * b.ym)};
}
}  // namespace

SolveRegion::SolveRegion(const Grid& grid, const LinearSolverSettings& solver)
    : grid_(grid), unknowns_per_cell_(grid.dimension() + 1), solver_settings_(solver), cells_(grid), index_(grid) {
  cells_.set(0.0);  // empty until assigned: the first step lays the band
  index_.set(-1.0);
  // The solver is made with the region's first matrix, in the first step. Made once now, it reads
  // the --petsc options of its prefix, so that one PETSc refuses stops the run before it starts
  // (and before --overwrite removes an earlier run).
  LinearSolver(grid.comm(), "coupled", solver_settings_);
}

SolveRegion::~SolveRegion() {
  solver_.reset();  // before the matrix it holds
}

bool SolveRegion::covers(const Field& needed) const {
  const auto& b = grid_.owned();
  const ConstFieldArray in_array(grid_.field_dm(), needed.global()), mine_array(grid_.field_dm(), cells_.global());
  const VolumeView in = in_array.volume(), mine = mine_array.volume();
  const BlockedView mask(grid_, blocked_);
  int missing = 0;
  for (int k = b.zs; k < b.ze() && !missing; ++k)
    for (int j = b.ys; j < b.ye() && !missing; ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        if (in[k][j][i] != 0.0 && mine[k][j][i] == 0.0 && !is_blocked(mask.data(), i, j, k)) {
          missing = 1;
          break;
        }
  int any = 0;
  MPI_Allreduce(&missing, &any, 1, MPI_INT, MPI_MAX, grid_.comm());
  return any == 0;
}

bool SolveRegion::laid() const {
  double most = 0.0;
  PetscCallAbort(PETSC_COMM_WORLD, VecMax(cells_.global(), nullptr, &most));
  return most > 0.0;
}

void SolveRegion::assign(const Field& wanted) {
  const auto& b = grid_.owned();
  {
    const ConstFieldArray in(grid_.field_dm(), wanted.global());
    FieldArray mine(grid_.field_dm(), cells_.global());
    const BlockedView mask(grid_, blocked_);
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          mine.volume()[k][j][i] = in.volume()[k][j][i] != 0.0 && !is_blocked(mask.data(), i, j, k) ? 1.0 : 0.0;
  }
  cells_.scatter_to_local();
}

long SolveRegion::prepare() {
  const MPI_Comm comm = grid_.comm();
  const auto& box = grid_.owned();
  candidate_.clear();
  {
    const ConstFieldArray mine(grid_.field_dm(), cells_.global());
    for (int k = box.zs; k < box.ze(); ++k)
      for (int j = box.ys; j < box.ye(); ++j)
        for (int i = box.xs; i < box.xe(); ++i)
          if (mine.volume()[k][j][i] != 0.0)
            candidate_.push_back(((k - box.zs) * box.ym + (j - box.ys)) * box.xm + (i - box.xs));
  }
  // The mask is compared rather than tracked: a retried step or a restart restores it directly.
  int changed = (!numbered_ || candidate_ != owned_) ? 1 : 0, any_changed = 0;
  MPI_Allreduce(&changed, &any_changed, 1, MPI_INT, MPI_MAX, comm);
  if (!any_changed) return cell_count_;

  if (solver_) solves_at_limit_before_ = solver_->solves_at_iteration_limit();
  solver_.reset();
  matrix_.reset();
  rhs_.reset();
  solution_.reset();
  owned_.swap(candidate_);
  numbered_ = true;
  const long local = long(owned_.size());
  long first = 0;
  MPI_Allreduce(&local, &cell_count_, 1, MPI_LONG, MPI_SUM, comm);
  MPI_Exscan(&local, &first, 1, MPI_LONG, MPI_SUM, comm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) first = 0;  // MPI_Exscan leaves rank 0's result undefined
  first_row_ = unknowns_per_cell_ * PetscInt(first);
  index_.set(-1.0);
  {
    FieldArray index(grid_.field_dm(), index_.global());
    for (size_t n = 0; n < owned_.size(); ++n) {
      const auto [i, j, k] = owned_cell(box, owned_[n]);
      index.volume()[k][j][i] = double(first + long(n));
    }
  }
  index_.scatter_to_local();
  if (cell_count_ == 0) return 0;  // no soil left: nothing but air at rest

  const PetscInt rows = unknowns_per_cell_ * PetscInt(local), entries = entries_per_row(grid_.dimension());
  PetscCallAbort(comm, MatCreate(comm, matrix_.put()));
  PetscCallAbort(comm, MatSetSizes(matrix_, rows, rows, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCallAbort(comm, MatSetType(matrix_, MATAIJ));
  PetscCallAbort(comm, MatSetBlockSize(matrix_, unknowns_per_cell_));
  PetscCallAbort(comm, MatSeqAIJSetPreallocation(matrix_, entries, nullptr));
  PetscCallAbort(comm, MatMPIAIJSetPreallocation(matrix_, entries, nullptr, entries, nullptr));
  PetscCallAbort(comm, MatSetOption(matrix_, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));  // rows are set where owned
  PetscCallAbort(comm, MatCreateVecs(matrix_, solution_.put(), rhs_.put()));
  // A new pattern needs a new factorisation analysis; a fresh solver also takes the new sizes.
  auto solver = std::make_unique<LinearSolver>(comm, "coupled", solver_settings_);
  solver->continue_count(solves_at_limit_before_);
  solver_ = std::move(solver);
  return cell_count_;
}

SolveRegion::RowWriter::RowWriter(SolveRegion& region)
    : region_(region),
      index_array_(region.grid_.field_dm(), region.index_.local()),
      index_(index_array_.volume()) {
  PetscCallAbort(region_.grid_.comm(), VecGetArray(region_.rhs_, &rhs_));
}

SolveRegion::RowWriter::~RowWriter() {
  const MPI_Comm comm = region_.grid_.comm();
  PetscCallAbort(region_.grid_.comm(), VecRestoreArray(region_.rhs_, &rhs_));
  PetscCallAbort(comm, MatAssemblyBegin(region_.matrix_, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(comm, MatAssemblyEnd(region_.matrix_, MAT_FINAL_ASSEMBLY));
}

// Copies the coupled state's region cells into the region's vector (into_region) or back.
void SolveRegion::copy_solution(Vec x, bool into_region) {
  const auto& box = grid_.owned();
  const CellUnknowns full(grid_.comm(), x, box, unknowns_per_cell_);
  PetscScalar* region;
  PetscCallAbort(grid_.comm(), VecGetArray(solution_, &region));
  for (size_t n = 0; n < owned_.size(); ++n) {
    const auto [i, j, k] = owned_cell(box, owned_[n]);
    for (int u = 0; u < unknowns_per_cell_; ++u) {
      if (into_region) region[unknowns_per_cell_ * n + u] = full(i, j, k, u);
      else full(i, j, k, u) = region[unknowns_per_cell_ * n + u];
    }
  }
  PetscCallAbort(grid_.comm(), VecRestoreArray(solution_, &region));
}

int SolveRegion::solve(Vec x) {
  copy_solution(x, true);  // the initial guess of an iterative solver
  solver_->set_operator(matrix_);
  const int iterations = solver_->solve(rhs_, solution_);
  copy_solution(x, false);
  return iterations;
}

int SolveRegion::solve_by_last_factorisation(Vec x, int krylov_iterations) {
  copy_solution(x, true);
  const int applications = solver_->solve_by_last_factorisation(rhs_, solution_, krylov_iterations);
  copy_solution(x, false);
  return applications;
}

}  // namespace granflow

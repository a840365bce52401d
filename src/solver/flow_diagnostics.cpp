// What the flow reports of itself between steps: Courant numbers, the largest speed and where it
// is, the largest divergence, the solves that stopped at their iteration limit (part of FlowSolver).
#include "solver/flow_solver.hpp"

#include <algorithm>
#include <cmath>

#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "mesh/obstacles.hpp"

namespace granflow {

double FlowSolver::max_courant(double dt, const Field* region) const {
  const auto& b = grid_.owned();
  ConstFieldArray fx = local_read(grid_, *face_[0]), fy = local_read(grid_, *face_[1]);
  std::unique_ptr<ConstFieldArray> mask;
  if (region) mask = std::make_unique<ConstFieldArray>(grid_.field_dm(), region->local());
  double co = 0.0;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      if (mask) {  // only cells with some of the region in their 3 x 3 neighbourhood
        double m = 0.0;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) m = std::max(m, (*mask)[j + dj][i + di]);
        if (m < 1e-6) continue;
      }
      co = larger_or_nan(co, (std::abs(fx[j][i]) + std::abs(fx[j][i - 1])) * 0.5 * dt / grid_.dx(i) +
                                 (std::abs(fy[j][i]) + std::abs(fy[j - 1][i])) * 0.5 * dt / grid_.dy(j));
    }
  return mpi_max(grid_.comm(), co);
}

long FlowSolver::solves_at_iteration_limit() const {
  long n = 0;
  for (const auto* s : {momentum_solver_[0].get(), momentum_solver_[1].get(), pressure_solver_.get(), coupled_solver_.get()})
    if (s) n += s->solves_at_iteration_limit();
  if (solve_region_) n += solve_region_->solves_at_iteration_limit();
  return n;
}

double FlowSolver::max_speed() const {
  double s = 0.0;
  for (int a = 0; a < 2; ++a) s = larger_or_nan(s, max_abs(grid_.comm(), vel_[a]->global()));  // NaN reaches the divergence check
  return s;
}

FlowSolver::FastestCell FlowSolver::fastest_cell() const {
  const auto& b = grid_.owned();
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  const BlockedView mask(grid_, blocked_);  // their local values mirror the flow's
  FastestCell f;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      if (is_blocked(mask.data(), i, j)) continue;
      const double s = std::hypot(u[j][i], v[j][i]);
      if (takes_the_lead(s, f.speed)) f = {s, grid_.xc(i), grid_.yc(j)};  // the first NaN wins, so it is found
    }
  struct {
    double speed;
    int rank;
  } mine{std::isfinite(f.speed) ? f.speed : HUGE_VAL, 0}, top{};
  MPI_Comm_rank(grid_.comm(), &mine.rank);
  MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, grid_.comm());
  double where[3] = {f.speed, f.x, f.y};
  MPI_Bcast(where, 3, MPI_DOUBLE, top.rank, grid_.comm());
  return {where[0], where[1], where[2]};
}

double FlowSolver::max_divergence() const {
  const auto& b = grid_.owned();
  ConstFieldArray fx = local_read(grid_, *face_[0]), fy = local_read(grid_, *face_[1]);
  double m = 0.0;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const double div = fx[j][i] * grid_.face_area(0, i, j, 1) - fx[j][i - 1] * grid_.face_area(0, i, j, -1) +
                         (fy[j][i] - fy[j - 1][i]) * grid_.face_area(1, i, j, 1);
      m = std::max(m, std::abs(div));
    }
  return mpi_max(grid_.comm(), m);
}

}  // namespace granflow

// What the flow reports of itself between steps: Courant numbers, the largest speed and where it
// is, the largest divergence, the solves that stopped at their iteration limit (part of FlowSolver).
#include "mesh/axis_views.hpp"
#include "solver/flow_solver.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "mesh/obstacles.hpp"

namespace granflow {

double FlowSolver::max_courant(double dt, const Field* region) const {
  const auto& b = grid_.owned();
  const AxisViews face_vel(grid_, face_);
  std::optional<ConstFieldArray> mask_array;
  const VolumeView mask = region ? mask_array.emplace(grid_.field_dm(), region->local()).volume() : nullptr;
  const int layers = dimension_ == 3 ? 1 : 0;  // the neighbourhood's reach along z
  double co = 0.0;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (mask) {  // only cells with some of the region in their 3 x 3 (x 3) neighbourhood
          double m = 0.0;
          for (int dk = -layers; dk <= layers; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) m = std::max(m, mask[k + dk][j + dj][i + di]);
          if (m < 1e-6) continue;
        }
        double cell = 0.0;
        for (int a = 0; a < dimension_; ++a) {
          const VolumeView f = face_vel.view[a];
          const int di = a == 0, dj = a == 1, dk = a == 2;
          cell += (std::abs(f[k][j][i]) + std::abs(f[k - dk][j - dj][i - di])) * 0.5 * dt /
                  grid_.width(a, index_along(a, i, j, k));
        }
        co = larger_or_nan(co, cell);
      }
  return mpi_max(grid_.comm(), co);
}

long FlowSolver::solves_at_iteration_limit() const {
  long n = 0;
  for (const auto* s : {momentum_solver_[0].get(), momentum_solver_[1].get(), momentum_solver_[2].get(),
                        pressure_solver_.get(), coupled_solver_.get()})
    if (s) n += s->solves_at_iteration_limit();
  if (solve_region_) n += solve_region_->solves_at_iteration_limit();
  return n;
}

double FlowSolver::max_speed() const {
  double s = 0.0;
  for (int a = 0; a < dimension_; ++a) s = larger_or_nan(s, max_abs(grid_.comm(), vel_[a]->global()));  // NaN reaches the divergence check
  return s;
}

FlowSolver::FastestCell FlowSolver::fastest_cell() const {
  const auto& b = grid_.owned();
  const AxisViews vel(grid_, vel_);
  const BlockedView mask(grid_, blocked_);  // their local values mirror the flow's
  FastestCell f;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j, k)) continue;
        const double u = vel.view[0][k][j][i], v = vel.view[1][k][j][i];
        const double s = dimension_ == 3 ? std::sqrt(u * u + v * v + vel.view[2][k][j][i] * vel.view[2][k][j][i])
                                         : std::hypot(u, v);
        if (takes_the_lead(s, f.speed)) f = {s, grid_.xc(i), grid_.yc(j), grid_.zc(k)};  // the first NaN wins, so it is found
      }
  struct {
    double speed;
    int rank;
  } mine{std::isfinite(f.speed) ? f.speed : HUGE_VAL, 0}, top{};
  MPI_Comm_rank(grid_.comm(), &mine.rank);
  MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, grid_.comm());
  double where[4] = {f.speed, f.x, f.y, f.z};
  MPI_Bcast(where, 4, MPI_DOUBLE, top.rank, grid_.comm());
  return {where[0], where[1], where[2], where[3]};
}

double FlowSolver::max_divergence() const {
  const auto& b = grid_.owned();
  const AxisViews face_vel(grid_, face_);
  double m = 0.0;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        double div = 0.0;
        for (int a = 0; a < dimension_; ++a) {
          const VolumeView f = face_vel.view[a];
          const double high = f[k][j][i], low = f[k - (a == 2)][j - (a == 1)][i - (a == 0)];
          // Only the x faces' areas differ between the sides (by their radii in r-z).
          div += a == 0 ? high * grid_.face_area(a, i, j, k, 1) - low * grid_.face_area(a, i, j, k, -1)
                        : (high - low) * grid_.face_area(a, i, j, k, 1);
        }
        m = std::max(m, std::abs(div));
      }
  return mpi_max(grid_.comm(), m);
}

}  // namespace granflow

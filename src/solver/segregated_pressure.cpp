// The segregated pressure step of FlowSolver (numerics.pressure_coupling = "projection" or "piso",
// [VoF] Eqs. 28-30): the face coefficients that say how a face's flux responds to a pressure jump,
// the pressure equation's matrix, and the solve that corrects the face fluxes and cell velocities.
#include <algorithm>
#include <cmath>
#include <optional>

#include "mesh/face_loop.hpp"
#include "solver/cell_faces.hpp"
#include "mesh/obstacles.hpp"
#include "operators/face_laplacian.hpp"
#include "mesh/axis_views.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

namespace {

// Predicted face velocity (Rhie-Chow) on face fg of cell P = (i, j, k): interpolated HbyA plus the
// old-time-level correction that keeps the steady state independent of dt.
double predicted_face_velocity(int i, int j, int k, const FaceGeometry& fg, VolumeView h, VolumeView w, VolumeView q0,
                               double face_old) {
  const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
  return 0.5 * (h[k][j][i] + h[kn][jn][in]) +
         0.5 * (w[k][j][i] + w[kn][jn][in]) * (face_old - 0.5 * (q0[k][j][i] + q0[kn][jn][in]));
}

}  // namespace

double FlowSolver::face_coefficient(VolumeView rau, VolumeView rho, int i, int j, int k, const FaceGeometry& fg) const {
  const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
  if (settings_.numerics.pressure_coupling == PressureCoupling::piso) return 0.5 * (rau[k][j][i] + rau[kn][jn][in]);
  return dt_ / (0.5 * (rho[k][j][i] + rho[kn][jn][in]));
}

// Pressure equation ([VoF] Eqs. 28-30): sum_f K_f (p_P - p_N) = -sum_f (predicted outward flux). An
// atmosphere's face holds the pressure there (its conductance on the diagonal); a wall's carries no flux.
void FlowSolver::assemble_pressure_matrix() {
  const AxisViews rau(grid_, pressure_mobility_);
  const ConstFieldArray rho = local_read(grid_, *rho_);
  assemble_face_laplacian(
      grid_, pressure_matrix_,
      [&](int axis, int sign, int i, int j, int k) {
        const FaceGeometry& fg = face_along(axis, sign);
        const double area = grid_.face_area(axis, i, j, k, sign);
        const double d = std::abs(grid_.centre(axis, index_along(axis, i + fg.di, j + fg.dj, k + fg.dk)) -
                                  grid_.centre(axis, index_along(axis, i, j, k)));
        return face_coefficient(rau.view[axis], rho.volume(), i, j, k, fg) * area / d;
      },
      [&](int axis, int sign, int i, int j, int k) {
        if (boundary(settings_.boundaries, side_of(axis, sign)).kind != BoundaryKind::atmosphere) return 0.0;
        const double d_half = 0.5 * grid_.width(axis, index_along(axis, i, j, k));
        return rau.view[axis][k][j][i] * grid_.face_area(axis, i, j, k, sign) / d_half;
      });
  pressure_solver_->set_operator(pressure_matrix_);
}

// One pressure step ([VoF] Eqs. 28-30): the right-hand side from the predicted face fluxes, the
// pressure solve, the corrected face and cell velocities.
int FlowSolver::solve_pressure() {
  assemble_pressure_rhs();
  if (pressure_null_space_) PetscCallAbort(grid_.comm(), MatNullSpaceRemove(pressure_null_space_, rhs_));
  const int iterations = pressure_solver_->solve(rhs_, p_->global());
  fill_scalar_ghosts(*p_);
  correct_velocities();
  fill_velocity_ghosts();
  if (!has_pressure_boundary_) hold_pressure_at_top();
  return iterations;
}

// The pressure equation's right-hand side: minus the net outflow of the predicted face velocities,
// with the atmosphere's pressure on its faces.
void FlowSolver::assemble_pressure_rhs() {
  const auto& b = grid_.owned();
  const auto& g = settings_.gravity;
  const AxisViews h(grid_, velocity_without_pressure_), ra(grid_, pressure_mobility_), w(grid_, old_time_share_);
  const AxisViews q0(grid_, vel_old_), face_old(grid_, face_old_), face_vel(grid_, face_), vel(grid_, vel_);
  const ConstFieldArray rho_array = local_read(grid_, *rho_);
  const VolumeView rho = rho_array.volume();
  const AxisViews source(grid_, face_source_, has_face_source() ? dimension_ : 0);
  const auto faces = cell_faces(dimension_);
  FieldArray r(grid_.field_dm(), rhs_);
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        double rhs = 0.0;
        for (const auto& fg : faces) {
          const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
          const double area = grid_.face_area(fg.axis, i, j, k, fg.sign);
          const VolumeView hv = h.view[fg.axis], rav = ra.view[fg.axis];
          if (grid_.outside(in, jn, kn)) {
            const auto& bc = boundary(settings_.boundaries, fg.side);
            if (bc.kind != BoundaryKind::atmosphere) {  // walls: no flux; an inlet's is given
              rhs -= fg.sign * imposed_normal_velocity(bc, grid_, fg.side, i, j, k) * area;
              continue;
            }
            const double d_half = 0.5 * grid_.width(fg.axis, index_along(fg.axis, i, j, k));
            const double pb = atmosphere_face_pressure(fg.side, i, j, k, rho, vel.view, face_vel.view);
            const double K = rav[k][j][i] * area / d_half;
            rhs -= fg.sign * (hv[k][j][i] + rav[k][j][i] * rho[k][j][i] * g[fg.axis]) * area;
            rhs += K * pb;
            continue;
          }
          const double ustar = predicted_face_velocity(i, j, k, fg, hv, w.view[fg.axis], q0.view[fg.axis],
                                                       on_face(face_old.view, i, j, k, fg));
          const double rA = face_coefficient(rav, rho, i, j, k, fg);
          const double rho_f = 0.5 * (rho[k][j][i] + rho[kn][jn][in]);
          const double surface_force = face_source_on(source.view, i, j, k, fg);
          rhs -= fg.sign * (ustar + rA * rho_f * g[fg.axis] - rA * ambient_weight(fg.axis) + rA * surface_force) * area;
        }
        r.volume()[k][j][i] = rhs;
      }
}

// Corrected face velocities (divergence-free to the solver tolerance) and face forces, then the cell
// velocities from the reconstructed cell force. Atmosphere face forces need the pressure just solved;
// at walls the face force is zero: the wall pressure is the hydrostatic extrapolation of the cell's, as
// for a zero-gradient p - rho g.x.
void FlowSolver::correct_velocities() {
  const auto& b = grid_.owned();
  compute_face_forces();
  const AxisViews h(grid_, velocity_without_pressure_), ra(grid_, pressure_mobility_), w(grid_, old_time_share_);
  const AxisViews q0(grid_, vel_old_), face_old(grid_, face_old_), ff(grid_, face_force_);
  const ConstFieldArray rho_array = local_read(grid_, *rho_);
  const VolumeView rho = rho_array.volume();
  fill_owned_faces_any(
      grid_, per_axis(face_),
      [&](int axis, int i, int j, int k) {
        const FaceGeometry& fg = face_along(axis, 1);
        const double star = predicted_face_velocity(i, j, k, fg, h.view[axis], w.view[axis], q0.view[axis],
                                                    face_old.view[axis][k][j][i]);
        return star + face_coefficient(ra.view[axis], rho, i, j, k, fg) * ff.view[axis][k][j][i];
      },
      [&](int axis, int i, int j, int k, int sign) {
        // Walls are impermeable and their face force stays zero (pressure hydrostatic at the wall); an
        // inlet's velocity is given.
        const Side side = side_of(axis, sign);
        const auto& bc = boundary(settings_.boundaries, side);
        if (bc.kind != BoundaryKind::atmosphere) return imposed_normal_velocity(bc, grid_, side, i, j, k);
        return h.view[axis][k][j][i] + ra.view[axis][k][j][i] * on_face(ff.view, i, j, k, face_along(axis, sign));
      });
  // Cell velocities from the reconstructed cell force.
  for (int c = 0; c < dimension_; ++c) {
    FieldArray q(grid_.field_dm(), vel_[c]->global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          q.volume()[k][j][i] = h.view[c][k][j][i] + ra.view[c][k][j][i] * cell_force(c, i, j, k, ff.view[c], rho);
  }
}

// A closed domain fixes its pressure only up to a constant, which the Krylov solve leaves wherever
// its iterations end; the yield stress of a granular phase reads the level. Held as the initial
// hydrostatic pressure holds it: zero on the top side on average (the top face pressure p_P + rho_P
// g_y dy/2, as at any wall). A constant changes no face force.
void FlowSolver::hold_pressure_at_top() {
  const auto& b = grid_.owned();
  const int ny = grid_.ny();
  double sums[2] = {0.0, 0.0};  // area-weighted top pressure, area
  {
    const ConstFieldArray p_array(grid_.field_dm(), p_->global()), rho_array(grid_.field_dm(), rho_->global());
    const VolumeView p = p_array.volume(), rho = rho_array.volume();
    const BlockedView mask(grid_, blocked_);
    const int j = ny - 1;
    if (b.ye() == ny)
      for (int k = b.zs; k < b.ze(); ++k)
        for (int i = b.xs; i < b.xe(); ++i) {
          if (is_blocked(mask.data(), i, j, k)) continue;  // an obstacle at the top: no fluid there
          const double area = grid_.face_area(1, i, j, k, 1.0);
          sums[0] += (p[k][j][i] + rho[k][j][i] * settings_.gravity[1] * 0.5 * grid_.dy(j)) * area;
          sums[1] += area;
        }
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, grid_.comm());
  if (sums[1] == 0.0) return;  // the top blocked all along: the pinned row's level stands
  PetscCallAbort(grid_.comm(), VecShift(p_->global(), -sums[0] / sums[1]));
  fill_scalar_ghosts(*p_);
}

}  // namespace granflow

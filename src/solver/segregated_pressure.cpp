// The segregated pressure step of FlowSolver (numerics.pressure_coupling = "projection" or "piso",
// [VoF] Eqs. 28-30): the face coefficients that say how a face's flux responds to a pressure jump,
// the pressure equation's matrix, and the solve that corrects the face fluxes and cell velocities.
#include <algorithm>
#include <cmath>

#include "mesh/face_loop.hpp"
#include "solver/cell_faces.hpp"
#include "mesh/obstacles.hpp"
#include "operators/face_laplacian.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

namespace {

// Predicted face velocity (Rhie-Chow) along an axis between P = (i, j) and N = (in, jn): interpolated
// HbyA plus the old-time-level correction that keeps the steady state independent of dt.
double predicted_face_velocity(int i, int j, int in, int jn, const double* const* h, const double* const* w,
                               const double* const* q0, double face_old) {
  return 0.5 * (h[j][i] + h[jn][in]) + 0.5 * (w[j][i] + w[jn][in]) * (face_old - 0.5 * (q0[j][i] + q0[jn][in]));
}

}  // namespace


double FlowSolver::face_coefficient(const double* const* rau, const double* const* rho, int i, int j, int in,
                                    int jn) const {
  if (settings_.numerics.pressure_coupling == PressureCoupling::piso) return 0.5 * (rau[j][i] + rau[jn][in]);
  return dt_ / (0.5 * (rho[j][i] + rho[jn][in]));
}

// Pressure equation ([VoF] Eqs. 28-30): sum_f K_f (p_P - p_N) = -sum_f (predicted outward flux). An
// atmosphere's face holds the pressure there (its conductance on the diagonal); a wall's carries no flux.
void FlowSolver::assemble_pressure_matrix() {
  ConstFieldArray rx = local_read(grid_, *pressure_mobility_[0]), ry = local_read(grid_, *pressure_mobility_[1]);
  ConstFieldArray rho = local_read(grid_, *rho_);
  assemble_face_laplacian(
      grid_, pressure_matrix_,
      [&](int axis, int sign, int i, int j, int) {
        const int in = i + (axis == 0 ? sign : 0), jn = j + (axis == 1 ? sign : 0);
        const double area = grid_.face_area(axis, i, j, sign);
        const double d = axis == 0 ? std::abs(grid_.xc(in) - grid_.xc(i)) : std::abs(grid_.yc(jn) - grid_.yc(j));
        return face_coefficient(axis == 0 ? rx.data() : ry.data(), rho.data(), i, j, in, jn) * area / d;
      },
      [&](int axis, int sign, int i, int j, int) {
        if (boundary(settings_.boundaries, side_of(axis, sign)).kind != BoundaryKind::atmosphere) return 0.0;
        const double d_half = 0.5 * (axis == 0 ? grid_.dx(i) : grid_.dy(j));
        return (axis == 0 ? rx : ry)[j][i] * grid_.face_area(axis, i, j, sign) / d_half;
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
  ConstFieldArray hx = local_read(grid_, *velocity_without_pressure_[0]), hy = local_read(grid_, *velocity_without_pressure_[1]);
  ConstFieldArray rx = local_read(grid_, *pressure_mobility_[0]), ry = local_read(grid_, *pressure_mobility_[1]);
  ConstFieldArray wx = local_read(grid_, *old_time_share_[0]), wy = local_read(grid_, *old_time_share_[1]);
  ConstFieldArray u0 = local_read(grid_, *vel_old_[0]), v0 = local_read(grid_, *vel_old_[1]);
  ConstFieldArray fx0 = local_read(grid_, *face_old_[0]), fy0 = local_read(grid_, *face_old_[1]);
  ConstFieldArray fxv = local_read(grid_, *face_[0]), fyv = local_read(grid_, *face_[1]);
  ConstFieldArray rho = local_read(grid_, *rho_), u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  FieldArray r(grid_.field_dm(), rhs_);
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      double rhs = 0.0;
      for (const auto& fg : faces_of_cell) {
        const int in = i + fg.di, jn = j + fg.dj;
        const double area = grid_.face_area(fg.axis, i, j, fg.sign);
        const double* const* h = fg.axis == 0 ? hx.data() : hy.data();
        const double* const* ra = fg.axis == 0 ? rx.data() : ry.data();
        if (grid_.outside(in, jn)) {
          const auto& bc = boundary(settings_.boundaries, fg.side);
          if (bc.kind != BoundaryKind::atmosphere) continue;  // walls: no flux
          const double d_half = 0.5 * (fg.axis == 0 ? grid_.dx(i) : grid_.dy(j));
          const double pb = atmosphere_face_pressure(fg.side, i, j, rho.data(), u.data(), v.data(), fxv.data(), fyv.data());
          const double K = ra[j][i] * area / d_half;
          rhs -= fg.sign * (h[j][i] + ra[j][i] * rho[j][i] * g[fg.axis]) * area;
          rhs += K * pb;
          continue;
        }
        const double* const* w = fg.axis == 0 ? wx.data() : wy.data();
        const double* const* q0 = fg.axis == 0 ? u0.data() : v0.data();
        const double face_old = fg.axis == 0 ? (fg.sign > 0 ? fx0[j][i] : fx0[j][i - 1])
                                             : (fg.sign > 0 ? fy0[j][i] : fy0[j - 1][i]);
        const double ustar = predicted_face_velocity(i, j, in, jn, h, w, q0, face_old);
        const double rA = face_coefficient(ra, rho.data(), i, j, in, jn);
        const double rho_f = 0.5 * (rho[j][i] + rho[jn][in]);
        rhs -= fg.sign * (ustar + rA * rho_f * g[fg.axis] - rA * ambient_weight(fg.axis)) * area;
      }
      r[j][i] = rhs;
    }
}

// Corrected face velocities (divergence-free to the solver tolerance) and face forces, then the cell
// velocities from the reconstructed cell force. Atmosphere face forces need the pressure just solved;
// at walls the face force is zero: the wall pressure is the hydrostatic extrapolation of the cell's, as
// for a zero-gradient p - rho g.x.
void FlowSolver::correct_velocities() {
  const auto& b = grid_.owned();
  compute_face_forces();
  ConstFieldArray hx = local_read(grid_, *velocity_without_pressure_[0]), hy = local_read(grid_, *velocity_without_pressure_[1]);
  ConstFieldArray rx = local_read(grid_, *pressure_mobility_[0]), ry = local_read(grid_, *pressure_mobility_[1]);
  ConstFieldArray wx = local_read(grid_, *old_time_share_[0]), wy = local_read(grid_, *old_time_share_[1]);
  ConstFieldArray u0 = local_read(grid_, *vel_old_[0]), v0 = local_read(grid_, *vel_old_[1]);
  ConstFieldArray fx0 = local_read(grid_, *face_old_[0]), fy0 = local_read(grid_, *face_old_[1]);
  ConstFieldArray rho = local_read(grid_, *rho_);
  ConstFieldArray ffx = local_read(grid_, *face_force_[0]), ffy = local_read(grid_, *face_force_[1]);
  const double* const* h[2] = {hx.data(), hy.data()};
  const double* const* ra[2] = {rx.data(), ry.data()};
  const double* const* w[2] = {wx.data(), wy.data()};
  const double* const* q0[2] = {u0.data(), v0.data()};
  const double* const* face_old[2] = {fx0.data(), fy0.data()};
  const double* const* ff[2] = {ffx.data(), ffy.data()};
  fill_owned_faces(
      grid_, *face_[0], *face_[1],
      [&](int axis, int i, int j) {
        const int in = axis == 0 ? i + 1 : i, jn = axis == 0 ? j : j + 1;
        const double star = predicted_face_velocity(i, j, in, jn, h[axis], w[axis], q0[axis], face_old[axis][j][i]);
        return star + face_coefficient(ra[axis], rho.data(), i, j, in, jn) * ff[axis][j][i];
      },
      [&](int axis, int i, int j, int sign) {
        // Walls are impermeable and their face force stays zero (pressure hydrostatic at the wall).
        if (boundary(settings_.boundaries, side_of(axis, sign)).kind != BoundaryKind::atmosphere) return 0.0;
        const int fi = axis == 0 && sign < 0 ? i - 1 : i, fj = axis == 1 && sign < 0 ? j - 1 : j;
        return h[axis][j][i] + ra[axis][j][i] * ff[axis][fj][fi];
      });
  // Cell velocities from the reconstructed cell force.
  FieldArray u(grid_.field_dm(), vel_[0]->global()), v(grid_.field_dm(), vel_[1]->global());
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      u[j][i] = hx[j][i] + rx[j][i] * cell_force(0, i, j, ffx.data(), rho.data());
      v[j][i] = hy[j][i] + ry[j][i] * cell_force(1, i, j, ffy.data(), rho.data());
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
    ConstFieldArray p(grid_.field_dm(), p_->global()), rho(grid_.field_dm(), rho_->global());
    const BlockedView mask(grid_, blocked_);
    if (b.ye() == ny)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, ny - 1)) continue;  // an obstacle at the top: no fluid there
        const double area = grid_.face_area(1, i, ny - 1, 1.0);
        sums[0] += (p[ny - 1][i] + rho[ny - 1][i] * settings_.gravity[1] * 0.5 * grid_.dy(ny - 1)) * area;
        sums[1] += area;
      }
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, grid_.comm());
  if (sums[1] == 0.0) return;  // the top blocked all along: the pinned row's level stands
  PetscCallAbort(grid_.comm(), VecShift(p_->global(), -sums[0] / sums[1]));
  fill_scalar_ghosts(*p_);
}

}  // namespace granflow

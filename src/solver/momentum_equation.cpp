// The momentum equation of FlowSolver ([VoF] Eq. 27): assembly of a_P v_P - sum a_nb v_nb = source +
// V f_P with implicit viscous and convective terms (deferred correction for the higher-order
// convection schemes), its solve per component, and HbyA, the velocity without the pressure force that
// the segregated pressure step and the Rhie-Chow face fluxes start from.
#include <algorithm>
#include <cmath>
#include <optional>

#include "operators/convection_scheme.hpp"
#include "operators/face_laplacian.hpp"
#include "operators/strain_rate.hpp"
#include "mesh/obstacles.hpp"
#include "solver/cell_faces.hpp"
#include "mesh/axis_views.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

namespace {

// The viscous stress on a boundary face (a side or an obstacle), by the two-point gradient from the
// cell centre to the wall: a wall holds every component at its velocity, a slip wall the normal one at
// zero, an atmosphere none (zero-gradient velocity; its lagged transpose part stays, side_force.cpp).
// normal_conductance is stress_factor mu A and tangential mu A, both without the half cell width; wall is
// the velocity the face holds (held_velocity).
void add_boundary_face_stress(const Grid& grid, const NumericsSettings& num, const BoundaryCondition& bc,
                              const std::array<double, 3>& wall, const VolumeView vel[], int i, int j, int k,
                              const FaceGeometry& fg,
                              double normal_conductance, double tangential_conductance, double extra[],
                              double src[]) {
  const int dimension = grid.dimension();
  const double d_half = 0.5 * grid.width(fg.axis, index_along(fg.axis, i, j, k));
  const double coeff = normal_conductance / d_half;  // the implicit share, applied to every component
  if (holds_velocity(bc)) {
    for (int c = 0; c < dimension; ++c) {
      extra[c] += coeff;
      src[c] += coeff * wall[c];  // a wall's normal component is zero
    }
  } else if (bc.kind == BoundaryKind::slip) {
    extra[fg.axis] += coeff;  // impermeable: normal component zero; no shear
  }
  if (!num.quadratic_wall_gradient || bc.kind == BoundaryKind::atmosphere) return;
  // Deferred correction from the two-point wall gradient to the quadratic one (cell_faces.hpp). The net
  // two-point stress is mu per tangential and stress_factor mu for the normal component.
  for (int c = 0; c < dimension; ++c) {
    if (bc.kind == BoundaryKind::slip && c != fg.axis) continue;  // no shear at a slip wall
    const double uw = wall[c];
    const double quadratic = wall_gradient(grid, vel[c], i, j, k, fg, uw, true);
    const double two_point = wall_gradient(grid, vel[c], i, j, k, fg, uw, false);
    src[c] -= (c == fg.axis ? normal_conductance : tangential_conductance) * (quadratic - two_point);
  }
}

// Deferred correction from the upwind face value to the higher-order one, times the outward flux
// (lagged in the outer iterations): what the source loses for the face of cell (i, j, k) on fg.
double deferred_convection_correction(const NumericsSettings& num, VolumeView q, int i, int j, int k,
                                      const FaceGeometry& fg, double flux) {
  const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
  double uu, up, dn;
  if (flux >= 0.0) {
    up = q[k][j][i];
    dn = q[kn][jn][in];
    uu = q[k - fg.dk][j - fg.dj][i - fg.di];
  } else {
    up = q[kn][jn][in];
    dn = q[k][j][i];
    uu = q[kn + fg.dk][jn + fg.dj][in + fg.di];
  }
  return flux * (face_value(num.convection, num.blending, uu, up, dn) - up);
}


}  // namespace

// Momentum ([VoF] Eq. 27): a_P v_P - sum a_nb v_nb = source + V f_P.

void FlowSolver::assemble_momentum(double dt) {
  const auto& b = grid_.owned();
  const auto& num = settings_.numerics;
  const int dim = dimension_;
  const auto faces = cell_faces(dim);
  const AxisViews vel(grid_, vel_), vel0(grid_, vel_old_), face_vel(grid_, face_), face_mu(grid_, face_mu_);
  const ConstFieldArray rho_array = local_read(grid_, *rho_), mu_array = local_read(grid_, *mu_);
  const VolumeView rho = rho_array.volume(), mu = mu_array.volume();
  // Conservative momentum transport ([VoF] Eq. 18 in divergence form): d(rho v)/dt + div(m v) with m
  // the mass flux of the soil fraction's advection, written with its mass balance as
  //   (rho^n V/dt + sum_in m) v_P - sum_in m v_nb = rho^n V/dt v^n + ...,
  // so soil entering a cell of air brings its own velocity. Otherwise (advective) the cell's density
  // times the face velocity, rho_P (v_P - v^n) V/dt + rho_P sum_in q (v_P - v_nb).
  // The momentum the step starts with is the carried one (models/mixture/carried_momentum.hpp): with
  // the arctan mixture, not rho^n v^n.
  std::optional<ConstFieldArray> rho0_array, momentum0_array;
  std::optional<AxisViews> mass_flux;
  VolumeView rho0 = nullptr, momentum_density0 = nullptr;
  if (carries_mass_transport()) {  // the coupled solve
    rho0 = rho0_array.emplace(grid_.field_dm(), start_density_->local()).volume();
    if (num.density_jump_keeps_kinetic_energy)
      momentum_density0 = momentum0_array.emplace(grid_.field_dm(), start_momentum_density_->global()).volume();
    mass_flux.emplace(grid_, mass_flux_);
  }
  std::optional<AxisViews> body_force;
  if (body_force_[0]) body_force.emplace(grid_, body_force_, dim, true);

  const double stress_factor = num.transpose_stress ? 2.0 : 1.0;  // implicit share, see below
  const BlockedView mask(grid_, blocked_);
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        const size_t n = (size_t(k - b.zs) * b.ym + (j - b.ys)) * b.xm + (i - b.xs);
        const double V = grid_.volume(i, j, k);
        const double rhoP = rho[k][j][i], muP = mu[k][j][i];
        const double a_time = (rho0 ? rho0[k][j][i] : rhoP) * V / dt;
        double a_nb[6] = {0, 0, 0, 0, 0, 0};
        double diag = a_time;
        double extra[3] = {0.0, 0.0, 0.0};
        double src[3] = {};
        const double old_momentum = momentum_density0 ? momentum_density0[k][j][i] * V / dt : a_time;
        for (int c = 0; c < dim; ++c) src[c] = old_momentum * vel0.view[c][k][j][i];
        if (body_force)
          for (int c = 0; c < dim; ++c) src[c] += V * body_force->view[c][k][j][i];
        for (const FaceGeometry& fg : faces) {
          const int f = int(&fg - box_faces);
          const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
          const double area = grid_.face_area(fg.axis, i, j, k, fg.sign);
          const bool is_obstacle = is_blocked(mask.data(), in, jn, kn);
          const bool is_boundary = grid_.outside(in, jn, kn) || is_obstacle;
          const double mu_face = on_face(face_mu.view, i, j, k, fg);
          // Full viscous stress div(mu (grad v + grad v^T)), split as in Jasak & Weller (2000): the
          // implicit part is 2 mu grad(v_c) on every face, and the lagged remainder on faces tangential
          // to c is mu [(d v_n / d x_c) - (d v_c / d n)]. The implicit part bounds the lagged one, so the
          // iteration is stable at any viscosity, and at convergence the stress is exactly the symmetric
          // one. Boundary faces read the ghosts, which encode the boundary condition.
          if (num.transpose_stress) {
            for (int c = 0; c < dim; ++c)
              if (c != fg.axis)
                src[c] += fg.sign * mu_face * lagged_transpose_gradient(grid_, vel.view, i, j, k, fg, c) * area;
          }
          if (is_boundary) {
            const auto& bc = is_obstacle ? obstacle_wall : boundary(settings_.boundaries, fg.side);
            const auto wall = is_obstacle ? bc.velocity : held_velocity(bc, grid_, fg.side, i, j, k);
            add_boundary_face_stress(grid_, num, bc, wall, vel.view, i, j, k, fg, stress_factor * mu_face * area,
                                     mu_face * area, extra, src);
            if (bc.kind == BoundaryKind::inlet) {  // the inflow brings the inlet's momentum, upwind
              const double inflow =  // kg/s
                  rho0 ? -fg.sign * area * on_face(mass_flux->view, i, j, k, fg)
                       : rhoP * (-fg.sign * on_face(face_vel.view, i, j, k, fg) * area);
              if (inflow > 0.0) {
                diag += inflow;
                // at the inlet's own velocity: on a face its opening cuts, the inflow (its open share)
                // enters at v_in over the open part, not at the face's mean
                for (int c = 0; c < dim; ++c) src[c] += inflow * bc.velocity[c];
              }
            }
            continue;
          }
          // Outward face velocity and flux.
          const double flux =  // outward mass flux, kg/s (per metre of depth on a planar mesh)
              rho0 ? fg.sign * area * on_face(mass_flux->view, i, j, k, fg)
                   : rhoP * (fg.sign * on_face(face_vel.view, i, j, k, fg) * area);
          const double d = std::abs(grid_.centre(fg.axis, index_along(fg.axis, in, jn, kn)) -
                                    grid_.centre(fg.axis, index_along(fg.axis, i, j, k)));
          a_nb[f] = stress_factor * mu_face * area / d + std::max(-flux, 0.0);
          diag += a_nb[f];
          if (num.convection != ConvectionScheme::upwind)
            for (int c = 0; c < dim; ++c) src[c] -= deferred_convection_correction(num, vel.view[c], i, j, k, fg, flux);
        }
        // Hoop stress of the radial momentum, implicit: -2 mu u_r / r^2 per volume of the full stress ([YS]
        // Sec. 4); -mu u_r / r^2 of div(mu grad v) alone (transpose_stress = false).
        if (grid_.axisymmetric()) extra[0] += stress_factor * muP * V / (grid_.xc(i) * grid_.xc(i));
        for (const FaceGeometry& fg : faces) a_neighbour_[&fg - box_faces][n] = a_nb[&fg - box_faces];
        for (int c = 0; c < dim; ++c) {
          a_centre_[c][n] = diag + extra[c];
          source_[c][n] = src[c];
        }
      }
}

int FlowSolver::solve_momentum() {
  const auto& b = grid_.owned();
  // The momentum matrices from assemble_momentum's coefficients (the coupled solve has its own).
  auto at = [&](int i, int j, int k) { return (size_t(k - b.zs) * b.ym + (j - b.ys)) * b.xm + (i - b.xs); };
  for (int c = 0; c < (shared_momentum_matrix_ ? 1 : dimension_); ++c) {
    Mat A = momentum_matrix_[c];
    assemble_star_rows(
        grid_, A,
        [&](int axis, int sign, int i, int j, int k) { return a_neighbour_[2 * axis + (sign < 0)][at(i, j, k)]; },
        [](int, int, int, int, int) { return 0.0; },
        [&](int i, int j, int k, double) { return a_centre_[c][at(i, j, k)]; });
    momentum_solver_[c]->set_operator(A);
  }
  int iterations = 0;
  for (int c = 0; c < dimension_; ++c) {
    {
      const ConstFieldArray ff = local_read(grid_, *face_force_[c]), rho = local_read(grid_, *rho_);
      FieldArray r(grid_.field_dm(), rhs_);
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i)
            r.volume()[k][j][i] =
                source_[c][at(i, j, k)] + grid_.volume(i, j, k) * cell_force(c, i, j, k, ff.volume(), rho.volume());
    }
    // Without slip walls the components have the same matrix: one operator, one preconditioner.
    iterations += momentum_solver_[shared_momentum_matrix_ ? 0 : c]->solve(rhs_, vel_[c]->global());
  }
  fill_velocity_ghosts();
  return iterations;
}

// HbyA = (source + sum a_nb v_nb) / a_P, rAU = V / a_P, and the share of the old time level in it.
void FlowSolver::compute_velocity_without_pressure() {
  const auto& b = grid_.owned();
  const ConstFieldArray rho_array = local_read(grid_, *rho_);
  const VolumeView rho = rho_array.volume();
  if (settings_.numerics.pressure_coupling == PressureCoupling::projection) {
    // Incremental projection: HbyA = v* - (dt/rho) f_old, so that the new velocity is HbyA + (dt/rho) f_new.
    for (int c = 0; c < dimension_; ++c) {
      const ConstFieldArray q = local_read(grid_, *vel_[c]), ff = local_read(grid_, *face_force_[c]);
      FieldArray h(grid_.field_dm(), velocity_without_pressure_[c]->global());
      FieldArray r(grid_.field_dm(), pressure_mobility_[c]->global());
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i) {
            double& rau = r.volume()[k][j][i];
            rau = dt_ / rho[k][j][i];
            h.volume()[k][j][i] = q.volume()[k][j][i] - rau * cell_force(c, i, j, k, ff.volume(), rho);
          }
    }
    for (int c = 0; c < dimension_; ++c) {
      velocity_without_pressure_[c]->scatter_to_local();
      pressure_mobility_[c]->scatter_to_local();
    }
    return;
  }
  const auto faces = cell_faces(dimension_);
  for (int c = 0; c < dimension_; ++c) {
    const ConstFieldArray q_array = local_read(grid_, *vel_[c]);
    const VolumeView q = q_array.volume();
    FieldArray h(grid_.field_dm(), velocity_without_pressure_[c]->global());
    FieldArray r(grid_.field_dm(), pressure_mobility_[c]->global());
    FieldArray w(grid_.field_dm(), old_time_share_[c]->global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const size_t n = (size_t(k - b.zs) * b.ym + (j - b.ys)) * b.xm + (i - b.xs);
          double H = source_[c][n];
          for (const FaceGeometry& fg : faces) {
            const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
            if (!grid_.outside(in, jn, kn)) H += a_neighbour_[&fg - box_faces][n] * q[kn][jn][in];
          }
          const double V = grid_.volume(i, j, k);
          h.volume()[k][j][i] = H / a_centre_[c][n];
          r.volume()[k][j][i] = V / a_centre_[c][n];
          w.volume()[k][j][i] = rho[k][j][i] * V / dt_ / a_centre_[c][n];
        }
  }
  for (int c = 0; c < dimension_; ++c) {
    velocity_without_pressure_[c]->scatter_to_local();
    pressure_mobility_[c]->scatter_to_local();
    old_time_share_[c]->scatter_to_local();
  }
}
}  // namespace granflow

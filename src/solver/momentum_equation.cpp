// The momentum equation of FlowSolver ([VoF] Eq. 27): assembly of a_P v_P - sum a_nb v_nb = source +
// V f_P with implicit viscous and convective terms (deferred correction for the higher-order
// convection schemes), its solve per component, and HbyA, the velocity without the pressure force that
// the segregated pressure step and the Rhie-Chow face fluxes start from.
#include <algorithm>
#include <cmath>

#include "operators/convection_scheme.hpp"
#include "operators/face_laplacian.hpp"
#include "operators/strain_rate.hpp"
#include "mesh/obstacles.hpp"
#include "solver/cell_faces.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

namespace {

// The viscous stress on a boundary face (a side or an obstacle), by the two-point gradient from the
// cell centre to the wall: a wall holds both components at its velocity, a slip wall the normal one at zero,
// an atmosphere neither (zero-gradient velocity; its lagged transpose part stays, side_force.cpp).
// normal_conductance is stress_factor mu A and tangential mu A, both without the half cell width.
void add_boundary_face_stress(const Grid& grid, const NumericsSettings& num, const BoundaryCondition& bc,
                              const double* const* const vel[2], int i, int j, const FaceGeometry& fg,
                              double normal_conductance, double tangential_conductance, double extra[2],
                              double src[2]) {
  const double d_half = 0.5 * (fg.axis == 0 ? grid.dx(i) : grid.dy(j));
  const double coeff = normal_conductance / d_half;  // the implicit share, applied to both components
  if (bc.kind == BoundaryKind::wall) {
    for (int c = 0; c < 2; ++c) {
      extra[c] += coeff;
      src[c] += coeff * (c == fg.axis ? 0.0 : bc.wall_velocity[c]);
    }
  } else if (bc.kind == BoundaryKind::slip) {
    extra[fg.axis] += coeff;  // impermeable: normal component zero; no shear
  }
  if (!num.quadratic_wall_gradient || bc.kind == BoundaryKind::atmosphere) return;
  // Deferred correction from the two-point wall gradient to the quadratic one (cell_faces.hpp). The net
  // two-point stress is mu per tangential and stress_factor mu for the normal component.
  for (int c = 0; c < 2; ++c) {
    if (bc.kind == BoundaryKind::slip && c != fg.axis) continue;  // no shear at a slip wall
    const double uw = c == fg.axis ? 0.0 : bc.wall_velocity[c];
    const double quadratic = wall_gradient(grid, vel[c], i, j, fg, uw, true);
    const double two_point = wall_gradient(grid, vel[c], i, j, fg, uw, false);
    src[c] -= (c == fg.axis ? normal_conductance : tangential_conductance) * (quadratic - two_point);
  }
}

// Deferred correction from the upwind face value to the higher-order one, times the outward flux
// (lagged in the outer iterations): what the source loses for the face of cell (i, j) on fg.
double deferred_convection_correction(const NumericsSettings& num, const double* const* q, int i, int j,
                                      const FaceGeometry& fg, double flux) {
  const int in = i + fg.di, jn = j + fg.dj;
  double uu, up, dn;
  if (flux >= 0.0) {
    up = q[j][i];
    dn = q[jn][in];
    uu = q[j - fg.dj][i - fg.di];
  } else {
    up = q[jn][in];
    dn = q[j][i];
    uu = q[jn + fg.dj][in + fg.di];
  }
  return flux * (face_value(num.convection, num.blending, uu, up, dn) - up);
}

}  // namespace

// Momentum ([VoF] Eq. 27): a_P v_P - sum a_nb v_nb = source + V f_P.

void FlowSolver::assemble_momentum(double dt) {
  const auto& b = grid_.owned();
  const auto& num = settings_.numerics;
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  ConstFieldArray u0 = local_read(grid_, *vel_old_[0]), v0 = local_read(grid_, *vel_old_[1]);
  ConstFieldArray fx = local_read(grid_, *face_[0]), fy = local_read(grid_, *face_[1]);
  ConstFieldArray rho = local_read(grid_, *rho_), mu = local_read(grid_, *mu_);
  ConstFieldArray fmx = local_read(grid_, *face_mu_[0]), fmy = local_read(grid_, *face_mu_[1]);
  const double* const* vel[2] = {u.data(), v.data()};
  // Conservative momentum transport ([VoF] Eq. 18 in divergence form): d(rho v)/dt + div(m v) with m
  // the mass flux of the soil fraction's advection, written with its mass balance as
  //   (rho^n V/dt + sum_in m) v_P - sum_in m v_nb = rho^n V/dt v^n + ...,
  // so soil entering a cell of air brings its own velocity. Otherwise (advective) the cell's density
  // times the face velocity, rho_P (v_P - v^n) V/dt + rho_P sum_in q (v_P - v_nb).
  std::unique_ptr<ConstFieldArray> rho0, mfx, mfy;
  if (carries_mass_transport()) {
    rho0 = std::make_unique<ConstFieldArray>(grid_.field_dm(), start_density_->local());
    mfx = std::make_unique<ConstFieldArray>(grid_.field_dm(), mass_flux_[0]->local());
    mfy = std::make_unique<ConstFieldArray>(grid_.field_dm(), mass_flux_[1]->local());
  }
  std::unique_ptr<ConstFieldArray> bx, by;
  if (body_force_[0]) {
    bx = std::make_unique<ConstFieldArray>(grid_.field_dm(), body_force_[0]->global());
    by = std::make_unique<ConstFieldArray>(grid_.field_dm(), body_force_[1]->global());
  }

  const double stress_factor = num.transpose_stress ? 2.0 : 1.0;  // implicit share, see below
  const BlockedView mask(grid_, blocked_);
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const size_t k = size_t(j - b.ys) * b.xm + (i - b.xs);
      const double V = grid_.volume(i, j);
      const double rhoP = rho[j][i], muP = mu[j][i];
      const double a_time = (rho0 ? (*rho0)[j][i] : rhoP) * V / dt;
      double a_nb[4] = {0, 0, 0, 0};
      double diag = a_time;
      double extra[2] = {0.0, 0.0};
      double src[2] = {a_time * u0[j][i], a_time * v0[j][i]};
      if (bx) {
        src[0] += V * (*bx)[j][i];
        src[1] += V * (*by)[j][i];
      }
      for (int f = 0; f < 4; ++f) {
        const FaceGeometry& fg = faces_of_cell[f];
        const int in = i + fg.di, jn = j + fg.dj;
        const double area = grid_.face_area(fg.axis, i, j, fg.sign);
        const bool is_obstacle = is_blocked(mask.data(), in, jn);
        const bool is_boundary = grid_.outside(in, jn) || is_obstacle;
        const double mu_face = on_face(fmx.data(), fmy.data(), i, j, fg);
        // Full viscous stress div(mu (grad v + grad v^T)), split as in Jasak & Weller (2000): the
        // implicit part is 2 mu grad(v_c) on every face, and the lagged remainder on faces tangential
        // to c is mu [(d v_n / d x_c) - (d v_c / d n)]. The implicit part bounds the lagged one, so the
        // iteration is stable at any viscosity, and at convergence the stress is exactly the symmetric
        // one. Boundary faces read the ghosts, which encode the boundary condition.
        if (num.transpose_stress) {
          for (int c = 0; c < 2; ++c)
            if (c != fg.axis) src[c] += fg.sign * mu_face * lagged_transpose_gradient(grid_, vel, i, j, fg, c) * area;
        }
        if (is_boundary) {
          const auto& bc = is_obstacle ? obstacle_wall : boundary(settings_.boundaries, fg.side);
          add_boundary_face_stress(grid_, num, bc, vel, i, j, fg, stress_factor * mu_face * area, mu_face * area,
                                   extra, src);
          continue;
        }
        // Outward face velocity and flux.
        const double flux =  // outward mass flux, kg/s per metre
            rho0 ? fg.sign * area * on_face(mfx->data(), mfy->data(), i, j, fg)
                 : rhoP * (fg.sign * on_face(fx.data(), fy.data(), i, j, fg) * area);
        const double d = fg.axis == 0 ? std::abs(grid_.xc(in) - grid_.xc(i)) : std::abs(grid_.yc(jn) - grid_.yc(j));
        a_nb[f] = stress_factor * mu_face * area / d + std::max(-flux, 0.0);
        diag += a_nb[f];
        if (num.convection != ConvectionScheme::upwind)
          for (int c = 0; c < 2; ++c) src[c] -= deferred_convection_correction(num, vel[c], i, j, fg, flux);
      }
      // Hoop stress of the radial momentum, implicit: -2 mu u_r / r^2 per volume of the full stress ([YS]
      // Sec. 4); -mu u_r / r^2 of div(mu grad v) alone (transpose_stress = false).
      if (grid_.axisymmetric()) extra[0] += stress_factor * muP * V / (grid_.xc(i) * grid_.xc(i));
      for (int f = 0; f < 4; ++f) a_neighbour_[f][k] = a_nb[f];
      for (int c = 0; c < 2; ++c) {
        a_centre_[c][k] = diag + extra[c];
        source_[c][k] = src[c];
      }
    }
}

int FlowSolver::solve_momentum() {
  const auto& b = grid_.owned();
  // The momentum matrices from assemble_momentum's coefficients (the coupled solve has its own).
  auto at = [&](int i, int j) { return size_t(j - b.ys) * b.xm + (i - b.xs); };
  for (int c = 0; c < (shared_momentum_matrix_ ? 1 : 2); ++c) {
    Mat A = momentum_matrix_[c];
    assemble_star_rows(
        grid_, A, [&](int axis, int sign, int i, int j, int) { return a_neighbour_[2 * axis + (sign < 0)][at(i, j)]; },
        [](int, int, int, int, int) { return 0.0; }, [&](int i, int j, int, double) { return a_centre_[c][at(i, j)]; });
    momentum_solver_[c]->set_operator(A);
  }
  int iterations = 0;
  for (int c = 0; c < 2; ++c) {
    {
      ConstFieldArray ff = local_read(grid_, *face_force_[c]), rho = local_read(grid_, *rho_);
      FieldArray r(grid_.field_dm(), rhs_);
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const size_t k = size_t(j - b.ys) * b.xm + (i - b.xs);
          r[j][i] = source_[c][k] + grid_.volume(i, j) * cell_force(c, i, j, ff.data(), rho.data());
        }
    }
    // Without slip walls both components have the same matrix: one operator, one preconditioner.
    iterations += momentum_solver_[shared_momentum_matrix_ ? 0 : c]->solve(rhs_, vel_[c]->global());
  }
  fill_velocity_ghosts();
  return iterations;
}

// HbyA = (source + sum a_nb v_nb) / a_P, rAU = V / a_P, and the share of the old time level in it.
void FlowSolver::compute_velocity_without_pressure() {
  const auto& b = grid_.owned();
  ConstFieldArray rho = local_read(grid_, *rho_);
  if (settings_.numerics.pressure_coupling == PressureCoupling::projection) {
    // Incremental projection: HbyA = v* - (dt/rho) f_old, so that the new velocity is HbyA + (dt/rho) f_new.
    for (int c = 0; c < 2; ++c) {
      ConstFieldArray q = local_read(grid_, *vel_[c]), ff = local_read(grid_, *face_force_[c]);
      FieldArray h(grid_.field_dm(), velocity_without_pressure_[c]->global());
      FieldArray r(grid_.field_dm(), pressure_mobility_[c]->global());
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          r[j][i] = dt_ / rho[j][i];
          h[j][i] = q[j][i] - r[j][i] * cell_force(c, i, j, ff.data(), rho.data());
        }
    }
    for (int c = 0; c < 2; ++c) {
      velocity_without_pressure_[c]->scatter_to_local();
      pressure_mobility_[c]->scatter_to_local();
    }
    return;
  }
  for (int c = 0; c < 2; ++c) {
    ConstFieldArray q = local_read(grid_, *vel_[c]);
    FieldArray h(grid_.field_dm(), velocity_without_pressure_[c]->global());
    FieldArray r(grid_.field_dm(), pressure_mobility_[c]->global());
    FieldArray w(grid_.field_dm(), old_time_share_[c]->global());
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        const size_t k = size_t(j - b.ys) * b.xm + (i - b.xs);
        double H = source_[c][k];
        for (int f = 0; f < 4; ++f) {
          const FaceGeometry& fg = faces_of_cell[f];
          if (!grid_.outside(i + fg.di, j + fg.dj)) H += a_neighbour_[f][k] * q[j + fg.dj][i + fg.di];
        }
        const double V = grid_.volume(i, j);
        h[j][i] = H / a_centre_[c][k];
        r[j][i] = V / a_centre_[c][k];
        w[j][i] = rho[j][i] * V / dt_ / a_centre_[c][k];
      }
  }
  for (int c = 0; c < 2; ++c) {
    velocity_without_pressure_[c]->scatter_to_local();
    pressure_mobility_[c]->scatter_to_local();
    old_time_share_[c]->scatter_to_local();
  }
}
}  // namespace granflow

// The coupled velocity-pressure solve of FlowSolver: momentum and continuity of one outer iteration
// as one linear system in (u, v, p), so that no splitting error decides how a face responds to a
// pressure jump. Faces carry Rhie-Chow fluxes with the mobility V/a_P (harmonic between the two
// cells): where viscosity holds a cell, its faces barely respond to pressure, so a rigid block next
// to air stays rigid; solved together with momentum, this small mobility cannot overshoot the way it
// does in a segregated (SIMPLE/PISO) pressure step.
#include <algorithm>
#include <cmath>

#include "mesh/obstacles.hpp"
#include "operators/face_interpolation.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

namespace {
enum Unknown { U = 0, V = 1, P = 2 };
}  // namespace

void FlowSolver::create_coupled_system() {
  MPI_Comm comm = grid_.comm();
  PetscInt m, n;
  const PetscInt *lx, *ly;
  PetscCallAbort(comm, DMDAGetInfo(grid_.field_dm(), nullptr, nullptr, nullptr, nullptr, &m, &n, nullptr, nullptr,
                                   nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCallAbort(comm, DMDAGetOwnershipRanges(grid_.field_dm(), &lx, &ly, nullptr));
  PetscCallAbort(comm, DMDACreate2d(comm, grid_.matrix_x_sides(), DM_BOUNDARY_NONE, DMDA_STENCIL_STAR, grid_.nx(),
                                    grid_.ny(), m, n, 3, 1, lx, ly, coupled_dm_.put()));
  PetscCallAbort(comm, DMSetUp(coupled_dm_));
  PetscCallAbort(comm, DMCreateGlobalVector(coupled_dm_, coupled_solution_.put()));
  // Over the soil and its air band (the region makes its own system), or over the whole domain.
  if (settings_.numerics.air_band > 0) {
    solve_region_ = std::make_unique<SolveRegion>(grid_, settings_.coupled_solver);
  } else {
    PetscCallAbort(comm, DMCreateMatrix(coupled_dm_, coupled_matrix_.put()));
    PetscCallAbort(comm, MatSetOption(coupled_matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCallAbort(comm, VecDuplicate(coupled_solution_, coupled_rhs_.put()));
    coupled_solver_ = std::make_unique<LinearSolver>(comm, "coupled", settings_.coupled_solver);
  }
  for (int a = 0; a < 2; ++a) {
    cell_force_[a] = std::make_unique<Field>(grid_);
    cell_force_[a]->set(0.0);
  }
}

bool FlowSolver::solve_region_covers(const Field& cells) const {
  return !solve_region_ || solve_region_->covers(cells);
}

bool FlowSolver::solve_region_laid() const { return solve_region_ && solve_region_->laid(); }

void FlowSolver::set_solve_region(const Field& cells) {
  if (solve_region_) solve_region_->assign(cells);
}

// Pressure of air at rest in row j below the top at the ambient pressure, as the initial pressure
// starts (gravity along y, checked by the case): p0 under an open top, 0 under a closed domain's top.
double FlowSolver::pressure_at_rest(double rho, int j) const {
  const double y_top = grid_.spec().upper[1];
  return ambient_pressure(settings_.boundaries) - rho * settings_.gravity[1] * (y_top - grid_.yc(j));
}

// Rhie-Chow mobility of the face between (i,j) and its neighbour (in,jn): harmonic mean of V/a_P.
double FlowSolver::coupled_mobility(const double* const* rau, int i, int j, int in, int jn) const {
  return face_mean(FaceViscosity::harmonic, rau[j][i], rau[jn][in]);
}

// Balanced cell force rho_P mean(f_face / rho_face) from the current pressure, kept for the lagged
// part of the Rhie-Chow flux (which would otherwise widen the stencil).
void FlowSolver::store_cell_forces() {
  compute_face_forces();
  const auto& b = grid_.owned();
  ConstFieldArray rho = local_read(grid_, *rho_);
  for (int c = 0; c < 2; ++c) {
    ConstFieldArray ff = local_read(grid_, *face_force_[c]);
    FieldArray fc(grid_.field_dm(), cell_force_[c]->global());
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) fc[j][i] = cell_force(c, i, j, ff.data(), rho.data());
  }
  for (int c = 0; c < 2; ++c) cell_force_[c]->scatter_to_local();
}

// The Rhie-Chow mobilities V / a_P per component, with ghosts.
void FlowSolver::compute_mobilities() {
  const auto& b = grid_.owned();
  {
    for (int c = 0; c < 2; ++c) {
      FieldArray r(grid_.field_dm(), pressure_mobility_[c]->global());
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          r[j][i] = grid_.volume(i, j) / a_centre_[c][size_t(j - b.ys) * b.xm + (i - b.xs)];
    }
    for (int c = 0; c < 2; ++c) pressure_mobility_[c]->scatter_to_local();
  }
}

// The rows of one outer iteration's coupled system, cell by cell, from the state they are linearised
// at: each row is handed to `emit(i, j, unknown, n, cols, vals, rhs)`. A blocked cell's faces to open
// cells are walls (mesh/obstacles.hpp): no flux, no face force, no coupling; the cell itself has no
// unknowns (outside the region, or held at rest).
class FlowSolver::CoupledRows {
 public:
  explicit CoupledRows(FlowSolver& flow)
      : f_(flow),
        grid_(flow.grid_),
        b_(flow.grid_.owned()),
        g_(flow.settings_.gravity),
        rho_(local_read(grid_, *flow.rho_)),
        u_(local_read(grid_, *flow.vel_[0])),
        v_(local_read(grid_, *flow.vel_[1])),
        fxv_(local_read(grid_, *flow.face_[0])),
        fyv_(local_read(grid_, *flow.face_[1])),
        rx_(local_read(grid_, *flow.pressure_mobility_[0])),
        ry_(local_read(grid_, *flow.pressure_mobility_[1])),
        fcx_(local_read(grid_, *flow.cell_force_[0])),
        fcy_(local_read(grid_, *flow.cell_force_[1])),
        p_now_(local_read(grid_, *flow.p_)),
        mask_(flow.grid_, flow.blocked_) {}

  double density(int i, int j) const { return rho_[j][i]; }

  // The rows of cell (i, j): held at rest if blocked, else its two momentum rows and its continuity row.
  template <class Emit>
  void cell(int i, int j, Emit&& emit) {
    if (is_blocked(mask_.data(), i, j)) {  // at rest, its pressure kept
      const double one = 1.0;
      for (int unknown : {int(U), int(V), int(P)}) {
        const MatStencil row{0, j, i, unknown};
        emit(i, j, unknown, 1, &row, &one, unknown == P ? p_now_[j][i] : 0.0);
      }
      return;
    }
    for (int c = 0; c < 2; ++c) momentum(i, j, c, emit);
    continuity(i, j, emit);
  }

 private:
  bool open_neighbour(int in, int jn) const { return !grid_.outside(in, jn) && !is_blocked(mask_.data(), in, jn); }

  // The pressure pb of the atmosphere at the boundary face of (i, j) on side s along `axis`, recorded
  // as the system took it; false where the side is a wall.
  bool boundary_pressure(int axis, int s, int i, int j, double& pb) {
    const Side bs = axis == 0 ? (s > 0 ? Side::east : Side::west) : (s > 0 ? Side::north : Side::south);
    if (boundary(f_.settings_.boundaries, bs).kind != BoundaryKind::atmosphere) return false;
    pb = f_.atmosphere_face_pressure(bs, i, j, rho_.data(), u_.data(), v_.data(), fxv_.data(), fyv_.data());
    f_.solved_boundary_pressure_[static_cast<int>(bs)][axis == 0 ? j : i] = pb;
    return true;
  }

  // Momentum row of component c: a_P v_P - sum a_nb v_nb - V f_cell(p) = source.
  template <class Emit>
  void momentum(int i, int j, int c, Emit&& emit) {
    const size_t k = size_t(j - b_.ys) * b_.xm + (i - b_.xs);
    const double Vol = grid_.volume(i, j), rhoP = rho_[j][i];
    MatStencil row{0, j, i, c};
    MatStencil cols[8];
    double vals[8];
    int n = 0;
    cols[n] = row;
    vals[n++] = f_.a_centre_[c][k];
    const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    for (int f = 0; f < 4; ++f) {
      const int in = i + di[f], jn = j + dj[f];
      if (!open_neighbour(in, jn)) continue;
      cols[n] = MatStencil{0, jn, in, c};
      vals[n++] = -f_.a_neighbour_[f][k];
    }
    double r = f_.source_[c][k];
    double p_centre = 0.0;
    for (int side = 0; side < 2; ++side) {  // high then low face along c
      const int s = side == 0 ? 1 : -1;
      const int in = i + (c == 0 ? s : 0), jn = j + (c == 1 ? s : 0);
      if (is_blocked(mask_.data(), in, jn)) continue;  // an obstacle's wall carries no face force
      if (grid_.outside(in, jn)) {
        const double d = 0.5 * (c == 0 ? grid_.dx(i) : grid_.dy(j));
        double pb;
        if (!boundary_pressure(c, s, i, j, pb)) continue;  // walls carry no face force
        // -V/2 f_b with f_b = -s (p_b - p_P)/d + rho_P g_c: p_b enters like a neighbour pressure.
        const double w = Vol / (2 * d);
        p_centre += -s * w;
        r += -s * w * pb + 0.5 * Vol * rhoP * g_[c];
        continue;
      }
      const double d = c == 0 ? std::abs(grid_.xc(in) - grid_.xc(i)) : std::abs(grid_.yc(jn) - grid_.yc(j));
      const double rho_f = 0.5 * (rhoP + rho_[jn][in]);
      const double w = Vol * rhoP / (2 * rho_f * d);  // -V rho_P/(2 rho_f) * (-s (p_N - p_P)/d)
      cols[n] = MatStencil{0, jn, in, P};
      vals[n++] = s * w;
      p_centre += -s * w;
      r += 0.5 * Vol * rhoP * (g_[c] - f_.ambient_weight(c) / rho_f);
    }
    cols[n] = MatStencil{0, j, i, P};
    vals[n++] = p_centre;
    emit(i, j, c, n, cols, vals, r);
  }

  // Continuity row: sum_f s A U_f = 0, U_f = mean(v_n) + m_f (f_f(p) - mean(f_cell)_lagged).
  template <class Emit>
  void continuity(int i, int j, Emit&& emit) {
    const double rhoP = rho_[j][i];
    const double* const* rau[2] = {rx_.data(), ry_.data()};
    const double* const* fcell[2] = {fcx_.data(), fcy_.data()};
    MatStencil row{0, j, i, P};
    MatStencil cols[12];
    double vals[12];
    int n = 0;
    double u_centre[2] = {0.0, 0.0}, p_centre = 0.0, r = 0.0;
    for (int f = 0; f < 4; ++f) {
      const int axis = f < 2 ? 0 : 1;
      const int s = (f % 2 == 0) ? 1 : -1;
      const int in = i + (axis == 0 ? s : 0), jn = j + (axis == 1 ? s : 0);
      const double area = grid_.face_area(axis, i, j, s);
      if (is_blocked(mask_.data(), in, jn)) continue;  // no flux through an obstacle's wall
      if (grid_.outside(in, jn)) {
        const double d = 0.5 * (axis == 0 ? grid_.dx(i) : grid_.dy(j));
        double pb;
        if (!boundary_pressure(axis, s, i, j, pb)) continue;
        const double m = rau[axis][j][i];
        u_centre[axis] += s * area;
        p_centre += m * area / d;
        r += m * area / d * pb - s * area * m * rhoP * g_[axis] + s * area * m * fcell[axis][j][i];
        continue;
      }
      const double d = axis == 0 ? std::abs(grid_.xc(in) - grid_.xc(i)) : std::abs(grid_.yc(jn) - grid_.yc(j));
      const double m = f_.coupled_mobility(rau[axis], i, j, in, jn);
      const double rho_f = 0.5 * (rhoP + rho_[jn][in]);
      u_centre[axis] += 0.5 * s * area;
      cols[n] = MatStencil{0, jn, in, axis};
      vals[n++] = 0.5 * s * area;
      p_centre += m * area / d;
      cols[n] = MatStencil{0, jn, in, P};
      vals[n++] = -m * area / d;
      r += -s * area * m * rho_f * g_[axis] + s * area * m * f_.ambient_weight(axis) +
           s * area * m * 0.5 * (fcell[axis][j][i] + fcell[axis][jn][in]);
    }
    cols[n] = MatStencil{0, j, i, U};
    vals[n++] = u_centre[0];
    cols[n] = MatStencil{0, j, i, V};
    vals[n++] = u_centre[1];
    cols[n] = row;
    vals[n++] = p_centre;
    if (f_.pins_pressure_level_ && i == f_.pin_i_ && j == f_.pin_j_) {
      // A closed domain's continuity rows sum to zero (every face's flux enters two of them with
      // opposite signs), so one of them is implied by the others; this cell's holds the pressure
      // level at the last iterate's instead, scaled like the row it replaces.
      std::fill(vals, vals + n - 1, 0.0);
      r = p_centre * p_now_[j][i];
    }
    emit(i, j, int(P), n, cols, vals, r);
  }

  FlowSolver& f_;
  const Grid& grid_;
  const CellBox& b_;
  const std::array<double, 3>& g_;
  ConstFieldArray rho_, u_, v_, fxv_, fyv_, rx_, ry_, fcx_, fcy_, p_now_;
  const BlockedView mask_;
};

// The coupled rows of velocity and pressure, over the air band's region or the whole domain.
void FlowSolver::fill_coupled_rows() {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  for (Side side : planar_sides)  // NaN: a face the system below does not hold (outside the air band's region)
    solved_boundary_pressure_[static_cast<int>(side)].assign(normal_axis(side) == 0 ? ny : nx, std::nan(""));
  CoupledRows rows(*this);
  if (solve_region_) {
    // Only the region's rows; outside, air at rest under the pressure of the air column above it.
    const long region_cells = solve_region_->prepare();
    // Without an open side nothing else fixes the pressure's level, unless the region leaves out some
    // cells, whose air at rest under a zero top then holds it. Blocked cells are never in the region:
    // it covers every open cell if it holds as many.
    pins_pressure_level_ = !has_pressure_boundary_ && region_cells == (blocked_ ? open_cells_ : long(nx) * ny);
    if (region_cells == 0) return;
    auto outside = [&](int i, int j, int unknown) {
      return unknown == P ? pressure_at_rest(rows.density(i, j), j) : 0.0;
    };
    SolveRegion::RowWriter region_rows(*solve_region_);
    auto emit = [&](int i, int j, int unknown, int n, const MatStencil* cols, const double* vals, double r) {
      region_rows.set(i, j, unknown, n, cols, vals, r, outside);
    };
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        if (region_rows.inside(i, j)) rows.cell(i, j, emit);
  } else {
    pins_pressure_level_ = !has_pressure_boundary_;
    PetscScalar*** rhs;
    PetscCallAbort(grid_.comm(), DMDAVecGetArrayDOF(coupled_dm_, coupled_rhs_, &rhs));
    auto emit = [&](int i, int j, int unknown, int n, const MatStencil* cols, const double* vals, double r) {
      const MatStencil row{0, j, i, unknown};
      PetscCallAbort(PETSC_COMM_SELF, MatSetValuesStencil(coupled_matrix_, 1, &row, n, cols, vals, INSERT_VALUES));
      rhs[j][i][unknown] = r;
    };
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) rows.cell(i, j, emit);
    PetscCallAbort(grid_.comm(), DMDAVecRestoreArrayDOF(coupled_dm_, coupled_rhs_, &rhs));
    PetscCallAbort(grid_.comm(), MatAssemblyBegin(coupled_matrix_, MAT_FINAL_ASSEMBLY));
    PetscCallAbort(grid_.comm(), MatAssemblyEnd(coupled_matrix_, MAT_FINAL_ASSEMBLY));
  }
}

// Solves the coupled rows from the current state and takes their solution as the state; the air
// outside a band's region at rest and hydrostatic. Returns the iterations.
int FlowSolver::solve_coupled_rows(bool by_first_factorisation) {
  const auto& b = grid_.owned();
  // Initial guess: the current state.
  {
    PetscScalar*** x;
    PetscCallAbort(grid_.comm(), DMDAVecGetArrayDOF(coupled_dm_, coupled_solution_, &x));
    ConstFieldArray u(grid_.field_dm(), vel_[0]->global()), v(grid_.field_dm(), vel_[1]->global()),
        p(grid_.field_dm(), p_->global());
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        x[j][i][U] = u[j][i];
        x[j][i][V] = v[j][i];
        x[j][i][P] = p[j][i];
      }
    PetscCallAbort(grid_.comm(), DMDAVecRestoreArrayDOF(coupled_dm_, coupled_solution_, &x));
  }
  int iterations = 0;
  if (solve_region_) {
    // Outside the region: air at rest under the pressure of the air column above it.
    ConstFieldArray inside(grid_.field_dm(), solve_region_->cells().global()), rho(grid_.field_dm(), rho_->global());
    PetscScalar*** x;
    PetscCallAbort(grid_.comm(), DMDAVecGetArrayDOF(coupled_dm_, coupled_solution_, &x));
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        if (inside[j][i] == 0.0) {
          x[j][i][U] = x[j][i][V] = 0.0;
          x[j][i][P] = pressure_at_rest(rho[j][i], j);
        }
    PetscCallAbort(grid_.comm(), DMDAVecRestoreArrayDOF(coupled_dm_, coupled_solution_, &x));
    if (solve_region_->cell_count() > 0)
      iterations = by_first_factorisation ? solve_region_->solve_by_last_factorisation(
                                                coupled_dm_, coupled_solution_, settings_.numerics.krylov_iterations)
                                          : solve_region_->solve(coupled_dm_, coupled_solution_);
  } else if (by_first_factorisation) {
    iterations = coupled_solver_->solve_by_last_factorisation(coupled_rhs_, coupled_solution_,
                                                               settings_.numerics.krylov_iterations);
  } else {
    coupled_solver_->set_operator(coupled_matrix_);
    iterations = coupled_solver_->solve(coupled_rhs_, coupled_solution_);
  }
  {
    PetscScalar*** x;
    PetscCallAbort(grid_.comm(), DMDAVecGetArrayDOF(coupled_dm_, coupled_solution_, &x));
    FieldArray u(grid_.field_dm(), vel_[0]->global()), v(grid_.field_dm(), vel_[1]->global()),
        p(grid_.field_dm(), p_->global());
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        u[j][i] = x[j][i][U];
        v[j][i] = x[j][i][V];
        p[j][i] = x[j][i][P];
      }
    PetscCallAbort(grid_.comm(), DMDAVecRestoreArrayDOF(coupled_dm_, coupled_solution_, &x));
  }
  return iterations;
}

void FlowSolver::update_coupled_face_velocities() {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  const auto& g = settings_.gravity;
  // Face velocities with exactly the flux of the continuity rows (divergence-free to the tolerance).
  // An atmosphere face keeps the pressure the rows were built with: with total pressure, inflow
  // enters at p0 - rho |v_P|^2 / 2, and v_P has just changed. Taken anew, it gave an open top under
  // a falling water column a flux of its own, and the water's volume grew by 2e-5.
  compute_face_forces();
  {
    ConstFieldArray p = local_read(grid_, *p_), rho = local_read(grid_, *rho_);
    for (int c = 0; c < 2; ++c) {
      FieldArray ff = local_array(grid_, *face_force_[c]);
      for (Side side : planar_sides) {
        if (normal_axis(side) != c) continue;
        const double sign = outward_normal(side, c);
        const auto& solved = solved_boundary_pressure_[static_cast<int>(side)];
        const bool low = sign < 0;
        if (c == 0 && grid_.owns_boundary(side))
          for (int j = b.ys; j < b.ye(); ++j) {
            const int i = low ? 0 : nx - 1;
            if (!std::isnan(solved[j]))
              ff[j][low ? -1 : i] = -sign * (solved[j] - p[j][i]) / (0.5 * grid_.dx(i)) + rho[j][i] * g[0];
          }
        if (c == 1 && (low ? b.ys == 0 : b.ye() == ny))
          for (int i = b.xs; i < b.xe(); ++i) {
            const int j = low ? 0 : ny - 1;
            if (!std::isnan(solved[i]))
              ff[low ? -1 : j][i] = -sign * (solved[i] - p[j][i]) / (0.5 * grid_.dy(j)) + rho[j][i] * g[1];
          }
      }
    }
  }
  {
    ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
    ConstFieldArray rx = local_read(grid_, *pressure_mobility_[0]), ry = local_read(grid_, *pressure_mobility_[1]);
    ConstFieldArray fcx = local_read(grid_, *cell_force_[0]), fcy = local_read(grid_, *cell_force_[1]);
    ConstFieldArray ffx = local_read(grid_, *face_force_[0]), ffy = local_read(grid_, *face_force_[1]);
    FieldArray fxv = local_array(grid_, *face_[0]), fyv = local_array(grid_, *face_[1]);
    const BlockedView mask(grid_, blocked_);
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs - 1; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j) || is_blocked(mask.data(), i + 1, j)) {
          fxv[j][i] = 0.0;  // an obstacle's wall
          continue;
        }
        if (grid_.outside(i, j) || grid_.outside(i + 1, j)) {
          const Side s = i == -1 ? Side::west : Side::east;
          const int ic = i == -1 ? 0 : i;
          fxv[j][i] = boundary(settings_.boundaries, s).kind == BoundaryKind::atmosphere
                          ? u[j][ic] + rx[j][ic] * (ffx[j][i] - fcx[j][ic])
                          : 0.0;
          continue;
        }
        fxv[j][i] = 0.5 * (u[j][i] + u[j][i + 1]) +
                    coupled_mobility(rx.data(), i, j, i + 1, j) * (ffx[j][i] - 0.5 * (fcx[j][i] + fcx[j][i + 1]));
      }
    for (int j = b.ys - 1; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j) || is_blocked(mask.data(), i, j + 1)) {
          fyv[j][i] = 0.0;
          continue;
        }
        if (j == -1 || j == ny - 1) {
          const Side s = j == -1 ? Side::south : Side::north;
          const int jc = j == -1 ? 0 : j;
          fyv[j][i] = boundary(settings_.boundaries, s).kind == BoundaryKind::atmosphere
                          ? v[jc][i] + ry[jc][i] * (ffy[j][i] - fcy[jc][i])
                          : 0.0;
          continue;
        }
        fyv[j][i] = 0.5 * (v[j][i] + v[j + 1][i]) +
                    coupled_mobility(ry.data(), i, j, i, j + 1) * (ffy[j][i] - 0.5 * (fcy[j][i] + fcy[j + 1][i]));
      }
  }
}

int FlowSolver::solve_coupled(bool by_first_factorisation) {
  // A later outer iteration keeps the first's mobilities: the continuity rows' entries are those and
  // the geometry alone, so they are the rows the first factorised, and the solve by that
  // factorisation holds them exactly. A step keeps its region, whose solver the first iteration
  // made; without a factorisation at hand (no soil in the region) the iteration factorises its own.
  const bool reuse = by_first_factorisation && (solve_region_ ? solve_region_->has_factorisation()
                                                              : coupled_solver_->has_preconditioner());
  if (!reuse) compute_mobilities();
  store_cell_forces();
  fill_coupled_rows();
  const int iterations = solve_coupled_rows(reuse);
  fill_velocity_ghosts();
  fill_scalar_ghosts(*p_);
  if (pins_pressure_level_) hold_pressure_at_top();  // the pinned level, moved to zero on the top
  update_coupled_face_velocities();
  return iterations;
}

}  // namespace granflow

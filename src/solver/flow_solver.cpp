#include "solver/flow_solver.hpp"

#include "mesh/face_loop.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "operators/convection_scheme.hpp"
#include "operators/face_interpolation.hpp"
#include "operators/strain_rate.hpp"

namespace granflow {

namespace {

// Geometry of one face of cell (i, j) in 2D planar coordinates (unit depth).
struct FaceGeometry {
  Side side;
  int axis;      // normal axis of the face
  double sign;   // +1 for the east/north face, -1 for west/south
  int di, dj;    // offset to the neighbour across the face
};
constexpr FaceGeometry faces_of_cell[4] = {
    {Side::east, 0, +1.0, +1, 0},
    {Side::west, 0, -1.0, -1, 0},
    {Side::north, 1, +1.0, 0, +1},
    {Side::south, 1, -1.0, 0, -1},
};

std::unique_ptr<Field> make_field(const Grid& g) { return std::make_unique<Field>(g); }

// Pressure at the cell centres of one column, hydrostatic below p_top at the top of the domain:
// the trapezoidal rule between centres, which is exactly what the face forces balance.
template <class Density>
void hydrostatic_column(const Grid& g, double gy, double p_top, Density rho, std::vector<double>& p) {
  const int ny = g.ny();
  p[ny - 1] = p_top - rho(ny - 1) * gy * 0.5 * g.dy(ny - 1);
  for (int j = ny - 2; j >= 0; --j) p[j] = p[j + 1] - 0.5 * (rho(j) + rho(j + 1)) * gy * (g.yc(j + 1) - g.yc(j));
}

double mpi_max(MPI_Comm comm, double v) {
  double r = v;
  MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MAX, comm);
  return r;
}

}  // namespace

FlowSolver::FlowSolver(const Grid& grid, const FlowSettings& settings) : grid_(grid), settings_(settings) {
  for (int a = 0; a < 2; ++a) {
    vel_[a] = make_field(grid);
    vel_old_[a] = make_field(grid);
    face_[a] = make_field(grid);
    face_old_[a] = make_field(grid);
    face_force_[a] = make_field(grid);
    hbya_[a] = make_field(grid);
    rau_[a] = make_field(grid);
    time_weight_[a] = make_field(grid);
    time_weight_[a]->set(0.0);  // stays zero under the projection coupling
    vel_[a]->set(0.0);
    face_[a]->set(0.0);
    face_force_[a]->set(0.0);
  }
  p_ = make_field(grid);
  rho_ = make_field(grid);
  mu_ = make_field(grid);
  p_->set(0.0);
  if (settings_.numerics.look_ahead_viscosity) {
    for (int a = 0; a < 2; ++a) {
      vel_ahead_[a] = make_field(grid);
      face_mu_now_[a] = make_field(grid);
    }
    mu_now_ = make_field(grid);
  }
  if (settings_.numerics.mean_viscosity_pressure) {
    p_last_iterate_ = make_field(grid);
    p_mean_ = make_field(grid);
  }
  rho_->set(1.0);
  mu_->set(1.0);
  for (auto& f : face_mu_) {
    f = make_field(grid);
    f->set(1.0);
  }

  const auto& box = grid.owned();
  const size_t n = size_t(box.xm) * box.ym;
  for (auto* v : {&a_east_, &a_west_, &a_north_, &a_south_, &a_centre_[0], &a_centre_[1], &source_[0], &source_[1],
                  &divergence_before_})
    v->assign(n, 0.0);

  MPI_Comm comm = grid.comm();
  for (int a = 0; a < 2; ++a) {
    PetscCallAbort(comm, DMCreateMatrix(grid.matrix_dm(), &momentum_matrix_[a]));
    momentum_solver_[a] = std::make_unique<LinearSolver>(comm, a == 0 ? "momentum_x" : "momentum_y",
                                                          settings.momentum_solver);
  }
  PetscCallAbort(comm, DMCreateMatrix(grid.matrix_dm(), &pressure_matrix_));
  pressure_solver_ = std::make_unique<LinearSolver>(comm, "pressure", settings.pressure_solver);
  PetscCallAbort(comm, DMCreateGlobalVector(grid.field_dm(), &rhs_));

  for (Side s : all_sides) {
    if (boundary(settings.boundaries, s).kind == BoundaryKind::atmosphere) has_pressure_boundary_ = true;
    if (boundary(settings.boundaries, s).kind == BoundaryKind::slip) shared_momentum_matrix_ = false;
  }
  if (settings.numerics.pressure_coupling == PressureCoupling::coupled) {
    if (!has_pressure_boundary_)
      throw std::invalid_argument("numerics.pressure_coupling = \"coupled\" needs an atmosphere boundary to fix the pressure level");
    create_coupled_system();
  }
  update_boundary_heads();
  if (!has_pressure_boundary_) {
    PetscCallAbort(comm, MatNullSpaceCreate(comm, PETSC_TRUE, 0, nullptr, &pressure_null_space_));
    PetscCallAbort(comm, MatSetNullSpace(pressure_matrix_, pressure_null_space_));
  }
}

void FlowSolver::enable_body_force() {
  for (int a = 0; a < 2; ++a)
    if (!body_force_[a]) {
      body_force_[a] = make_field(grid_);
      body_force_[a]->set(0.0);
    }
}

FlowSolver::~FlowSolver() {
  destroy_coupled_system();
  for (auto& m : momentum_matrix_) MatDestroy(&m);
  MatDestroy(&pressure_matrix_);
  MatNullSpaceDestroy(&pressure_null_space_);
  VecDestroy(&rhs_);
}

// ---------------------------------------------------------------------------------------------
// Ghosts: interior ghosts come from neighbouring ranks; ghosts outside the domain encode the
// boundary conditions (mirror images), so that stencils near walls need no special cases.

void FlowSolver::fill_scalar_ghosts(Field& f) {
  f.scatter_to_local();
  FieldArray a = local_array(grid_, f);
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  for (int k = 1; k <= Grid::ghost_width; ++k) {
    for (int j = b.ys - Grid::ghost_width; j < b.ye() + Grid::ghost_width; ++j) {
      if (b.xs == 0) a[j][-k] = a[j][0];
      if (b.xe() == nx) a[j][nx - 1 + k] = a[j][nx - 1];
    }
  }
  for (int k = 1; k <= Grid::ghost_width; ++k) {
    for (int i = b.xs - Grid::ghost_width; i < b.xe() + Grid::ghost_width; ++i) {
      if (b.ys == 0) a[-k][i] = a[0][i];
      if (b.ye() == ny) a[ny - 1 + k][i] = a[ny - 1][i];
    }
  }
}

void FlowSolver::fill_velocity_ghosts() {
  for (int a = 0; a < 2; ++a) vel_[a]->scatter_to_local();
  FieldArray u(grid_.field_dm(), vel_[0]->local()), v(grid_.field_dm(), vel_[1]->local());
  double** comp[2] = {u.data(), v.data()};
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  // value of the ghost at distance k outside a boundary whose mirror interior cell holds `inner`
  auto ghost = [](const BoundaryCondition& bc, int axis, int normal, double inner, double first) {
    switch (bc.kind) {
      case BoundaryKind::wall: return 2.0 * bc.wall_velocity[axis] - inner;
      case BoundaryKind::slip: return axis == normal ? -inner : inner;
      case BoundaryKind::atmosphere: return first;
    }
    return inner;
  };
  for (int a = 0; a < 2; ++a) {
    double** f = comp[a];
    for (int k = 1; k <= Grid::ghost_width; ++k) {
      for (int j = b.ys - Grid::ghost_width; j < b.ye() + Grid::ghost_width; ++j) {
        if (b.xs == 0) f[j][-k] = ghost(boundary(settings_.boundaries, Side::west), a, 0, f[j][k - 1], f[j][0]);
        if (b.xe() == nx)
          f[j][nx - 1 + k] = ghost(boundary(settings_.boundaries, Side::east), a, 0, f[j][nx - k], f[j][nx - 1]);
      }
    }
    for (int k = 1; k <= Grid::ghost_width; ++k) {
      for (int i = b.xs - Grid::ghost_width; i < b.xe() + Grid::ghost_width; ++i) {
        if (b.ys == 0) f[-k][i] = ghost(boundary(settings_.boundaries, Side::south), a, 1, f[k - 1][i], f[0][i]);
        if (b.ye() == ny)
          f[ny - 1 + k][i] = ghost(boundary(settings_.boundaries, Side::north), a, 1, f[ny - k][i], f[ny - 1][i]);
      }
    }
  }
}

void FlowSolver::refresh_ghosts() {
  fill_velocity_ghosts();
  fill_scalar_ghosts(*p_);
  fill_scalar_ghosts(*rho_);
  fill_scalar_ghosts(*mu_);
}

void FlowSolver::update_properties() {
  if (property_update_) property_update_(*this);
  fill_scalar_ghosts(*rho_);
  fill_scalar_ghosts(*mu_);
  if (face_viscosity_update_) face_viscosity_update_(*this);
  else face_viscosity_from_cells();
  update_boundary_heads();
}

// Face viscosity as the mean of the two cells' (numerics.face_viscosity); a boundary face takes its
// cell's. Covers the faces of the owned cells, reading the ghosts of mu.
void FlowSolver::face_viscosity_from_cells() {
  const auto kind = settings_.numerics.face_viscosity;
  ConstFieldArray mu = local_read(grid_, *mu_);
  fill_owned_faces(
      grid_, *face_mu_[0], *face_mu_[1],
      [&](int axis, int i, int j) { return face_mean(kind, mu[j][i], axis == 0 ? mu[j][i + 1] : mu[j + 1][i]); },
      [&](int, int i, int j, int) { return mu[j][i]; });
}

void FlowSolver::sync_velocity_from_cells() {
  fill_velocity_ghosts();
  const auto& b = grid_.owned();
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  FieldArray fx = local_array(grid_, *face_[0]), fy = local_array(grid_, *face_[1]);
  for (int j = b.ys - 1; j < b.ye(); ++j)
    for (int i = b.xs - 1; i < b.xe(); ++i) {
      const bool x_boundary = (i == -1 || i == grid_.nx() - 1);
      const bool y_boundary = (j == -1 || j == grid_.ny() - 1);
      if (j >= b.ys) fx[j][i] = x_boundary ? 0.0 : 0.5 * (u[j][i] + u[j][i + 1]);
      if (i >= b.xs) fy[j][i] = y_boundary ? 0.0 : 0.5 * (v[j][i] + v[j + 1][i]);
    }
}

// ---------------------------------------------------------------------------------------------
// Hydrostatic initial pressure.

void FlowSolver::set_hydrostatic_pressure() {
  const double gy = settings_.gravity[1];
  if (settings_.gravity[0] != 0.0)
    throw std::invalid_argument("a hydrostatic initial pressure needs gravity along the y axis");
  // Every rank needs whole columns of density: gather them (once, at start-up).
  Vec natural, all;
  VecScatter to_all;
  PetscCallAbort(grid_.comm(), DMDACreateNaturalVector(grid_.field_dm(), &natural));
  PetscCallAbort(grid_.comm(), DMDAGlobalToNaturalBegin(grid_.field_dm(), rho_->global(), INSERT_VALUES, natural));
  PetscCallAbort(grid_.comm(), DMDAGlobalToNaturalEnd(grid_.field_dm(), rho_->global(), INSERT_VALUES, natural));
  PetscCallAbort(grid_.comm(), VecScatterCreateToAll(natural, &to_all, &all));
  PetscCallAbort(grid_.comm(), VecScatterBegin(to_all, natural, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCallAbort(grid_.comm(), VecScatterEnd(to_all, natural, all, INSERT_VALUES, SCATTER_FORWARD));
  const double* rho_all;
  VecGetArrayRead(all, &rho_all);
  const int nx = grid_.nx(), ny = grid_.ny();
  auto rho_at = [&](int i, int j) { return rho_all[size_t(j) * nx + i]; };
  const auto& top = boundary(settings_.boundaries, Side::north);
  const double p_top = top.kind == BoundaryKind::atmosphere ? top.pressure : 0.0;
  const auto& b = grid_.owned();
  std::vector<double> column(ny);
  {
    FieldArray p(grid_.field_dm(), p_->global());
    for (int i = b.xs; i < b.xe(); ++i) {
      hydrostatic_column(grid_, gy, p_top, [&](int j) { return rho_at(i, j); }, column);
      for (int j = b.ys; j < b.ye(); ++j) p[j][i] = column[j];
    }
  }
  VecRestoreArrayRead(all, &rho_all);
  VecScatterDestroy(&to_all);
  VecDestroy(&all);
  VecDestroy(&natural);
  fill_scalar_ghosts(*p_);
  update_boundary_heads();
  // Face forces of the resting state: zero at walls (no flux), from the pressure elsewhere.
  for (int a = 0; a < 2; ++a) face_force_[a]->set(0.0);
  compute_face_forces();
}

// ---------------------------------------------------------------------------------------------
// Face forces -grad(p) + rho_f g on faces. Wall faces carry none (their entries stay zero);
// atmosphere faces use the boundary pressure.

double atmosphere_pressure(const BoundaryCondition& bc, double hydrostatic_head, double rho, double outward_velocity,
                           double speed2) {
  double p = bc.pressure + hydrostatic_head;
  if (bc.total_pressure && outward_velocity < 0.0) p -= 0.5 * rho * speed2;  // inflow: total pressure p0
  return p;
}

// Hydrostatic head of the fluid in the boundary columns of the west and east sides, integrated down
// from the top like the initial pressure. An open side then carries the weight of what actually lies
// in its column: soil leaving through it is not pushed back by a column of soil reaching to the top
// (which the adjacent cell's density would imply), and a layer at rest across it stays at rest.
void FlowSolver::update_boundary_heads() {
  const int nx = grid_.nx(), ny = grid_.ny();
  const auto& b = grid_.owned();
  const double gy = settings_.gravity[1];
  std::vector<double> rho_column(2 * size_t(ny), 0.0), all(2 * size_t(ny), 0.0);
  {
    ConstFieldArray rho(grid_.field_dm(), rho_->global());
    for (int j = b.ys; j < b.ye(); ++j) {
      if (b.xs == 0) rho_column[j] = rho[j][0];
      if (b.xe() == nx) rho_column[ny + j] = rho[j][nx - 1];
    }
  }
  MPI_Allreduce(rho_column.data(), all.data(), 2 * ny, MPI_DOUBLE, MPI_SUM, grid_.comm());
  for (int s = 0; s < 2; ++s) {
    const double* r = all.data() + size_t(s) * ny;
    side_head_[s].resize(ny);
    hydrostatic_column(grid_, gy, 0.0, [r](int j) { return r[j]; }, side_head_[s]);
  }
}

double FlowSolver::boundary_head(Side s, int j, double rho, double y_face) const {
  if (s == Side::west) return side_head_[0][j];
  if (s == Side::east) return side_head_[1][j];
  return rho * settings_.gravity[1] * (y_face - grid_.spec().upper[1]);
}

void FlowSolver::compute_face_forces() {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  const auto& g = settings_.gravity;
  ConstFieldArray p = local_read(grid_, *p_), rho = local_read(grid_, *rho_);
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  ConstFieldArray fx_vel = local_read(grid_, *face_[0]), fy_vel = local_read(grid_, *face_[1]);
  FieldArray fx = local_array(grid_, *face_force_[0]), fy = local_array(grid_, *face_force_[1]);
  auto boundary_force = [&](Side s, int i, int j, double face_vel) {
    const auto& bc = boundary(settings_.boundaries, s);
    const int axis = normal_axis(s);
    const double sign = outward_normal(s, axis);
    const double d = 0.5 * (axis == 0 ? grid_.dx(i) : grid_.dy(j));
    const double yb = grid_.yc(j) + (axis == 1 ? sign * d : 0.0);
    const double pb = atmosphere_pressure(bc, boundary_head(s, j, rho[j][i], yb), rho[j][i], sign * face_vel,
                                          u[j][i] * u[j][i] + v[j][i] * v[j][i]);
    return -sign * (pb - p[j][i]) / d + rho[j][i] * g[axis];
  };
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs - 1; i < b.xe(); ++i) {
      if (i == -1) {
        if (boundary(settings_.boundaries, Side::west).kind == BoundaryKind::atmosphere)
          fx[j][i] = boundary_force(Side::west, 0, j, fx_vel[j][i]);
      } else if (i == nx - 1) {
        if (boundary(settings_.boundaries, Side::east).kind == BoundaryKind::atmosphere)
          fx[j][i] = boundary_force(Side::east, i, j, fx_vel[j][i]);
      } else {
        fx[j][i] = -(p[j][i + 1] - p[j][i]) / (grid_.xc(i + 1) - grid_.xc(i)) + 0.5 * (rho[j][i] + rho[j][i + 1]) * g[0];
      }
    }
  for (int j = b.ys - 1; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      if (j == -1) {
        if (boundary(settings_.boundaries, Side::south).kind == BoundaryKind::atmosphere)
          fy[j][i] = boundary_force(Side::south, i, 0, fy_vel[j][i]);
      } else if (j == ny - 1) {
        if (boundary(settings_.boundaries, Side::north).kind == BoundaryKind::atmosphere)
          fy[j][i] = boundary_force(Side::north, i, j, fy_vel[j][i]);
      } else {
        fy[j][i] = -(p[j + 1][i] - p[j][i]) / (grid_.yc(j + 1) - grid_.yc(j)) + 0.5 * (rho[j][i] + rho[j + 1][i]) * g[1];
      }
    }
}

// ---------------------------------------------------------------------------------------------
// How face forces act on cells and faces, per pressure coupling:
//  - projection: accelerations f/rho_f are averaged to the cell (balanced force), and the face
//    coefficient is dt/rho_f. Stable at any ratio of viscous to inertial stiffness: the pressure step
//    never overshoots, because dt/rho bounds the inverse momentum operator from above.
//  - piso: forces are averaged to the cell and the face coefficient is the interpolated V/a_P
//    (Rhie-Chow). With a momentum predictor it overshoots where viscosity dominates a_P; without one
//    (velocity from HbyA of the previous iterate) it is stable and keeps rigid regions rigid.

double FlowSolver::cell_force(int axis, int i, int j, const double* const* ff, const double* const* rho) const {
  const int di = axis == 0 ? 1 : 0, dj = 1 - di;
  if (settings_.numerics.pressure_coupling == PressureCoupling::piso) return 0.5 * (ff[j][i] + ff[j - dj][i - di]);
  const double rho_hi = (axis == 0 ? i + 1 < grid_.nx() : j + 1 < grid_.ny()) ? 0.5 * (rho[j][i] + rho[j + dj][i + di]) : rho[j][i];
  const double rho_lo = (axis == 0 ? i > 0 : j > 0) ? 0.5 * (rho[j][i] + rho[j - dj][i - di]) : rho[j][i];
  return rho[j][i] * 0.5 * (ff[j][i] / rho_hi + ff[j - dj][i - di] / rho_lo);
}

double FlowSolver::face_coefficient(const double* const* rau, const double* const* rho, int i, int j, int in,
                                    int jn) const {
  if (settings_.numerics.pressure_coupling == PressureCoupling::piso) return 0.5 * (rau[j][i] + rau[jn][in]);
  return dt_ / (0.5 * (rho[j][i] + rho[jn][in]));
}

// The viscosity that sets the rotational correction of a cell: the smallest among it and its
// neighbours. Where viscosity jumps, the divergence in a stiff cell comes from flow on its soft
// side, and multiplying it by the stiff viscosity would overshoot by the contrast.
double FlowSolver::local_min_viscosity(const double* const* mu, int i, int j) const {
  double m = mu[j][i];
  if (i > 0) m = std::min(m, mu[j][i - 1]);
  if (i + 1 < grid_.nx()) m = std::min(m, mu[j][i + 1]);
  if (j > 0) m = std::min(m, mu[j - 1][i]);
  if (j + 1 < grid_.ny()) m = std::min(m, mu[j + 1][i]);
  return m;
}

// ---------------------------------------------------------------------------------------------
// Momentum ([VoF] Eq. 27): a_P v_P - sum a_nb v_nb = source + V f_P.

void FlowSolver::assemble_momentum(double dt) {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  const auto& num = settings_.numerics;
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  ConstFieldArray u0 = local_read(grid_, *vel_old_[0]), v0 = local_read(grid_, *vel_old_[1]);
  ConstFieldArray fx = local_read(grid_, *face_[0]), fy = local_read(grid_, *face_[1]);
  ConstFieldArray rho = local_read(grid_, *rho_), mu = local_read(grid_, *mu_);
  ConstFieldArray fmx = local_read(grid_, *face_mu_[0]), fmy = local_read(grid_, *face_mu_[1]);
  const double* const* vel[2] = {u.data(), v.data()};
  std::unique_ptr<ConstFieldArray> bx, by;
  if (body_force_[0]) {
    bx = std::make_unique<ConstFieldArray>(grid_.field_dm(), body_force_[0]->global());
    by = std::make_unique<ConstFieldArray>(grid_.field_dm(), body_force_[1]->global());
  }

  const double stress_factor = num.transpose_stress ? 2.0 : 1.0;  // implicit share, see below
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const size_t k = size_t(j - b.ys) * b.xm + (i - b.xs);
      const double dx = grid_.dx(i), dy = grid_.dy(j), V = grid_.volume(i, j);
      const double rhoP = rho[j][i], muP = mu[j][i];
      const double a_time = rhoP * V / dt;
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
        const bool is_boundary = in < 0 || in >= nx || jn < 0 || jn >= ny;
        const double mu_face = fg.axis == 0 ? fmx[j][fg.sign > 0 ? i : i - 1] : fmy[fg.sign > 0 ? j : j - 1][i];
        // Full viscous stress div(mu (grad v + grad v^T)), split as in Jasak & Weller (2000): the
        // implicit part is 2 mu grad(v_c) on every face, and the lagged remainder on faces tangential
        // to c is mu [(d v_n / d x_c) - (d v_c / d n)]. The implicit part bounds the lagged one, so the
        // iteration is stable at any viscosity, and at convergence the stress is exactly the symmetric
        // one. Boundary faces read the ghosts, which encode the boundary condition.
        if (num.transpose_stress) {
          for (int c = 0; c < 2; ++c) {
            if (c == fg.axis) continue;
            const double* const* qn = vel[fg.axis];  // normal component, differentiated along c
            const double* const* qc = vel[c];        // component c, differentiated along the normal
            double tangential;
            if (c == 0)  // d v_n / dx at a north/south face
              tangential = 0.5 * ((qn[j][i + 1] - qn[j][i - 1]) / (grid_.xc(i + 1) - grid_.xc(i - 1)) +
                                  (qn[jn][i + 1] - qn[jn][i - 1]) / (grid_.xc(i + 1) - grid_.xc(i - 1)));
            else  // d v_n / dy at an east/west face
              tangential = 0.5 * ((qn[j + 1][i] - qn[j - 1][i]) / (grid_.yc(j + 1) - grid_.yc(j - 1)) +
                                  (qn[j + 1][in] - qn[j - 1][in]) / (grid_.yc(j + 1) - grid_.yc(j - 1)));
            const double dn = fg.axis == 0 ? grid_.xc(in) - grid_.xc(i) : grid_.yc(jn) - grid_.yc(j);
            const double normal = (qc[jn][in] - qc[j][i]) / dn;
            src[c] += fg.sign * mu_face * (tangential - normal) * area;
          }
        }
        if (is_boundary) {
          const auto& bc = boundary(settings_.boundaries, fg.side);
          const double d_half = 0.5 * (fg.axis == 0 ? dx : dy);
          const double coeff = stress_factor * mu_face * area / d_half;
          if (bc.kind == BoundaryKind::wall) {
            for (int c = 0; c < 2; ++c) {
              extra[c] += coeff;
              src[c] += coeff * (c == fg.axis ? 0.0 : bc.wall_velocity[c]);
            }
          } else if (bc.kind == BoundaryKind::slip) {
            extra[fg.axis] += coeff;  // impermeable: normal component zero; no shear
          }
          if (num.quadratic_wall_gradient && bc.kind != BoundaryKind::atmosphere) {
            // Deferred correction from the two-point wall gradient (u_1 - u_w)/s1 to the quadratic one
            // through the wall and the first two cell centres (at s1 and s2 from the wall). The net
            // two-point stress is mu per tangential and stress_factor mu for the normal component.
            const double h1 = fg.axis == 0 ? dx : dy;
            const double h2 = fg.axis == 0 ? grid_.dx(i - fg.di) : grid_.dy(j - fg.dj);
            const double s1 = 0.5 * h1, s2 = h1 + 0.5 * h2;
            for (int c = 0; c < 2; ++c) {
              if (bc.kind == BoundaryKind::slip && c != fg.axis) continue;  // no shear at a slip wall
              const double uw = c == fg.axis ? 0.0 : bc.wall_velocity[c];
              const double u1 = vel[c][j][i], u2 = vel[c][j - fg.dj][i - fg.di];
              const double quadratic = quadratic_wall_derivative(u1, u2, uw, s1, s2);
              const double two_point = (u1 - uw) / s1;
              const double factor = c == fg.axis ? stress_factor : 1.0;
              src[c] -= factor * mu_face * area * (quadratic - two_point);
            }
          }
          continue;  // atmosphere: zero gradient, no viscous flux; convection has no correction
        }
        // Outward face velocity and flux.
        const double face_vel = fg.axis == 0 ? (fg.sign > 0 ? fx[j][i] : fx[j][i - 1])
                                             : (fg.sign > 0 ? fy[j][i] : fy[j - 1][i]);
        const double flux = fg.sign * face_vel * area;
        const double d = fg.axis == 0 ? std::abs(grid_.xc(in) - grid_.xc(i)) : std::abs(grid_.yc(jn) - grid_.yc(j));
        const double mu_f = mu_face;
        const double conv = rhoP * std::max(-flux, 0.0);
        a_nb[f] = stress_factor * mu_f * area / d + conv;
        diag += a_nb[f];
        // Deferred correction to the higher-order face value (lagged in the outer iterations).
        if (num.convection != ConvectionScheme::upwind) {
          for (int c = 0; c < 2; ++c) {
            const double* const* q = vel[c];
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
            src[c] -= rhoP * flux * (face_value(num.convection, num.blending, uu, up, dn) - up);
          }
        }
      }
      // Hoop stress of the radial momentum, -2 mu u_r / r^2 per volume ([YS] Sec. 4), implicit.
      if (grid_.axisymmetric()) extra[0] += 2.0 * muP * V / (grid_.xc(i) * grid_.xc(i));
      a_east_[k] = a_nb[0];
      a_west_[k] = a_nb[1];
      a_north_[k] = a_nb[2];
      a_south_[k] = a_nb[3];
      for (int c = 0; c < 2; ++c) {
        a_centre_[c][k] = diag + extra[c];
        source_[c][k] = src[c];
      }
    }
}

int FlowSolver::solve_momentum() {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  // The momentum matrices from assemble_momentum's coefficients (the coupled solve has its own).
  for (int c = 0; c < (shared_momentum_matrix_ ? 1 : 2); ++c) {
    Mat A = momentum_matrix_[c];
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        const size_t k = size_t(j - b.ys) * b.xm + (i - b.xs);
        MatStencil row{0, j, i, 0};
        MatStencil cols[5];
        double vals[5];
        int n = 0;
        cols[n] = row;
        vals[n++] = a_centre_[c][k];
        if (i + 1 < nx) { cols[n] = MatStencil{0, j, i + 1, 0}; vals[n++] = -a_east_[k]; }
        if (i - 1 >= 0) { cols[n] = MatStencil{0, j, i - 1, 0}; vals[n++] = -a_west_[k]; }
        if (j + 1 < ny) { cols[n] = MatStencil{0, j + 1, i, 0}; vals[n++] = -a_north_[k]; }
        if (j - 1 >= 0) { cols[n] = MatStencil{0, j - 1, i, 0}; vals[n++] = -a_south_[k]; }
        MatSetValuesStencil(A, 1, &row, n, cols, vals, INSERT_VALUES);
      }
    PetscCallAbort(grid_.comm(), MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCallAbort(grid_.comm(), MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
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
void FlowSolver::compute_hbya() {
  const auto& b = grid_.owned();
  ConstFieldArray rho = local_read(grid_, *rho_);
  if (settings_.numerics.pressure_coupling == PressureCoupling::projection) {
    // Incremental projection: HbyA = v* - (dt/rho) f_old, so that the new velocity is HbyA + (dt/rho) f_new.
    for (int c = 0; c < 2; ++c) {
      ConstFieldArray q = local_read(grid_, *vel_[c]), ff = local_read(grid_, *face_force_[c]);
      FieldArray h(grid_.field_dm(), hbya_[c]->global());
      FieldArray r(grid_.field_dm(), rau_[c]->global());
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          r[j][i] = dt_ / rho[j][i];
          h[j][i] = q[j][i] - r[j][i] * cell_force(c, i, j, ff.data(), rho.data());
        }
    }
    for (int c = 0; c < 2; ++c) {
      hbya_[c]->scatter_to_local();
      rau_[c]->scatter_to_local();
    }
    return;
  }
  for (int c = 0; c < 2; ++c) {
    ConstFieldArray q = local_read(grid_, *vel_[c]);
    FieldArray h(grid_.field_dm(), hbya_[c]->global());
    FieldArray r(grid_.field_dm(), rau_[c]->global());
    FieldArray w(grid_.field_dm(), time_weight_[c]->global());
    const int nx = grid_.nx(), ny = grid_.ny();
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        const size_t k = size_t(j - b.ys) * b.xm + (i - b.xs);
        double H = source_[c][k];
        if (i + 1 < nx) H += a_east_[k] * q[j][i + 1];
        if (i > 0) H += a_west_[k] * q[j][i - 1];
        if (j + 1 < ny) H += a_north_[k] * q[j + 1][i];
        if (j > 0) H += a_south_[k] * q[j - 1][i];
        const double V = grid_.volume(i, j);
        h[j][i] = H / a_centre_[c][k];
        r[j][i] = V / a_centre_[c][k];
        w[j][i] = rho[j][i] * V / dt_ / a_centre_[c][k];
      }
  }
  for (int c = 0; c < 2; ++c) {
    hbya_[c]->scatter_to_local();
    rau_[c]->scatter_to_local();
    time_weight_[c]->scatter_to_local();
  }
}

// Pressure equation ([VoF] Eqs. 28-30): sum_f K_f (p_P - p_N) = -sum_f (predicted outward flux).
void FlowSolver::assemble_pressure_matrix(double) {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  ConstFieldArray rx = local_read(grid_, *rau_[0]), ry = local_read(grid_, *rau_[1]);
  ConstFieldArray rho = local_read(grid_, *rho_);
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      MatStencil row{0, j, i, 0};
      MatStencil cols[5];
      double vals[5];
      int n = 1;
      cols[0] = row;
      double diag = 0.0;
      for (const auto& fg : faces_of_cell) {
        const int in = i + fg.di, jn = j + fg.dj;
        const double area = grid_.face_area(fg.axis, i, j, fg.sign);
        const double* const* r = fg.axis == 0 ? rx.data() : ry.data();
        if (in < 0 || in >= nx || jn < 0 || jn >= ny) {
          if (boundary(settings_.boundaries, fg.side).kind == BoundaryKind::atmosphere) {
            const double d_half = 0.5 * (fg.axis == 0 ? grid_.dx(i) : grid_.dy(j));
            diag += r[j][i] * area / d_half;
          }
          continue;
        }
        const double d = fg.axis == 0 ? std::abs(grid_.xc(in) - grid_.xc(i)) : std::abs(grid_.yc(jn) - grid_.yc(j));
        const double K = face_coefficient(r, rho.data(), i, j, in, jn) * area / d;
        diag += K;
        cols[n] = MatStencil{0, jn, in, 0};
        vals[n++] = -K;
      }
      vals[0] = diag;
      MatSetValuesStencil(pressure_matrix_, 1, &row, n, cols, vals, INSERT_VALUES);
    }
  PetscCallAbort(grid_.comm(), MatAssemblyBegin(pressure_matrix_, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(grid_.comm(), MatAssemblyEnd(pressure_matrix_, MAT_FINAL_ASSEMBLY));
  pressure_solver_->set_operator(pressure_matrix_);
}

int FlowSolver::solve_pressure(double) {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  const auto& g = settings_.gravity;
  int iterations = 0;
  // Predicted face velocity (Rhie-Chow) along `axis` between P=(i,j) and N=(i+di, j+dj): interpolated
  // HbyA plus the old-time-level correction that keeps the steady state independent of dt.
  auto predicted = [](int i, int j, int in, int jn, const double* const* h, const double* const* w,
                      const double* const* q0, double face_old) {
    return 0.5 * (h[j][i] + h[jn][in]) + 0.5 * (w[j][i] + w[jn][in]) * (face_old - 0.5 * (q0[j][i] + q0[jn][in]));
  };
  {
    ConstFieldArray hx = local_read(grid_, *hbya_[0]), hy = local_read(grid_, *hbya_[1]);
    ConstFieldArray rx = local_read(grid_, *rau_[0]), ry = local_read(grid_, *rau_[1]);
    ConstFieldArray wx = local_read(grid_, *time_weight_[0]), wy = local_read(grid_, *time_weight_[1]);
    ConstFieldArray u0 = local_read(grid_, *vel_old_[0]), v0 = local_read(grid_, *vel_old_[1]);
    ConstFieldArray fx0 = local_read(grid_, *face_old_[0]), fy0 = local_read(grid_, *face_old_[1]);
    ConstFieldArray fxv = local_read(grid_, *face_[0]), fyv = local_read(grid_, *face_[1]);
    ConstFieldArray rho = local_read(grid_, *rho_), u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
    FieldArray r(grid_.field_dm(), rhs_);
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        double rhs = 0.0;
        // Net outflow of the predicted cell velocity v*, linearly interpolated: its divergence feeds
        // the rotational correction. (Not the Rhie-Chow flux: its pressure-smoothing part is what
        // the projection itself corrects, and feeding it back would amplify pressure checkerboards.)
        double outflow = 0.0;
        for (const auto& fg : faces_of_cell) {
          const int in = i + fg.di, jn = j + fg.dj;
          const double area = grid_.face_area(fg.axis, i, j, fg.sign);
          const double* const* h = fg.axis == 0 ? hx.data() : hy.data();
          const double* const* ra = fg.axis == 0 ? rx.data() : ry.data();
          if (in < 0 || in >= nx || jn < 0 || jn >= ny) {
            const auto& bc = boundary(settings_.boundaries, fg.side);
            if (bc.kind != BoundaryKind::atmosphere) continue;  // walls: no flux
            const double d_half = 0.5 * (fg.axis == 0 ? grid_.dx(i) : grid_.dy(j));
            const double yb = grid_.yc(j) + (fg.axis == 1 ? fg.sign * d_half : 0.0);
            const double face_vel = fg.axis == 0 ? (fg.sign > 0 ? fxv[j][i] : fxv[j][i - 1])
                                                 : (fg.sign > 0 ? fyv[j][i] : fyv[j - 1][i]);
            const double pb = atmosphere_pressure(bc, boundary_head(fg.side, j, rho[j][i], yb), rho[j][i],
                                                  fg.sign * face_vel, u[j][i] * u[j][i] + v[j][i] * v[j][i]);
            const double K = ra[j][i] * area / d_half;
            rhs -= fg.sign * (h[j][i] + ra[j][i] * rho[j][i] * g[fg.axis]) * area;
            rhs += K * pb;
            outflow += fg.sign * (fg.axis == 0 ? u[j][i] : v[j][i]) * area;
            continue;
          }
          const double* const* w = fg.axis == 0 ? wx.data() : wy.data();
          const double* const* q0 = fg.axis == 0 ? u0.data() : v0.data();
          const double face_old = fg.axis == 0 ? (fg.sign > 0 ? fx0[j][i] : fx0[j][i - 1])
                                               : (fg.sign > 0 ? fy0[j][i] : fy0[j - 1][i]);
          const double ustar = predicted(i, j, in, jn, h, w, q0, face_old);
          const double rA = face_coefficient(ra, rho.data(), i, j, in, jn);
          const double rho_f = 0.5 * (rho[j][i] + rho[jn][in]);
          rhs -= fg.sign * (ustar + rA * rho_f * g[fg.axis]) * area;
          outflow += fg.sign * 0.5 * (fg.axis == 0 ? u[j][i] + u[jn][in] : v[j][i] + v[jn][in]) * area;
        }
        r[j][i] = rhs;
        divergence_before_[size_t(j - b.ys) * b.xm + (i - b.xs)] = outflow / grid_.volume(i, j);
      }
  }
  if (pressure_null_space_) MatNullSpaceRemove(pressure_null_space_, rhs_);
  iterations = pressure_solver_->solve(rhs_, p_->global());
  fill_scalar_ghosts(*p_);

  // Corrected face velocities (divergence-free to the solver tolerance) and face forces. Atmosphere
  // face forces need the pressure just solved; at walls the face force is zero: the wall pressure is
  // the hydrostatic extrapolation of the cell's, as for a zero-gradient p - rho g.x.
  compute_face_forces();
  {
    ConstFieldArray hx = local_read(grid_, *hbya_[0]), hy = local_read(grid_, *hbya_[1]);
    ConstFieldArray rx = local_read(grid_, *rau_[0]), ry = local_read(grid_, *rau_[1]);
    ConstFieldArray wx = local_read(grid_, *time_weight_[0]), wy = local_read(grid_, *time_weight_[1]);
    ConstFieldArray u0 = local_read(grid_, *vel_old_[0]), v0 = local_read(grid_, *vel_old_[1]);
    ConstFieldArray fx0 = local_read(grid_, *face_old_[0]), fy0 = local_read(grid_, *face_old_[1]);
    ConstFieldArray rho = local_read(grid_, *rho_);
    FieldArray fxv = local_array(grid_, *face_[0]), fyv = local_array(grid_, *face_[1]);
    FieldArray ffx = local_array(grid_, *face_force_[0]), ffy = local_array(grid_, *face_force_[1]);
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs - 1; i < b.xe(); ++i) {
        if (i == -1 || i == nx - 1) {
          const Side s = i == -1 ? Side::west : Side::east;
          const int ic = i == -1 ? 0 : i;
          if (boundary(settings_.boundaries, s).kind == BoundaryKind::atmosphere) {
            fxv[j][i] = hx[j][ic] + rx[j][ic] * ffx[j][i];
          } else {
            fxv[j][i] = 0.0;  // impermeable; the face force stays zero (pressure hydrostatic at the wall)
          }
          continue;
        }
        const double ustar = predicted(i, j, i + 1, j, hx.data(), wx.data(), u0.data(), fx0[j][i]);
        fxv[j][i] = ustar + face_coefficient(rx.data(), rho.data(), i, j, i + 1, j) * ffx[j][i];
      }
    for (int j = b.ys - 1; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (j == -1 || j == ny - 1) {
          const Side s = j == -1 ? Side::south : Side::north;
          const int jc = j == -1 ? 0 : j;
          if (boundary(settings_.boundaries, s).kind == BoundaryKind::atmosphere) {
            fyv[j][i] = hy[jc][i] + ry[jc][i] * ffy[j][i];
          } else {
            fyv[j][i] = 0.0;  // impermeable; the face force stays zero (pressure hydrostatic at the wall)
          }
          continue;
        }
        const double vstar = predicted(i, j, i, j + 1, hy.data(), wy.data(), v0.data(), fy0[j][i]);
        fyv[j][i] = vstar + face_coefficient(ry.data(), rho.data(), i, j, i, j + 1) * ffy[j][i];
      }
    // Cell velocities from the reconstructed cell force.
    FieldArray u(grid_.field_dm(), vel_[0]->global()), v(grid_.field_dm(), vel_[1]->global());
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        u[j][i] = hx[j][i] + rx[j][i] * cell_force(0, i, j, ffx.data(), rho.data());
        v[j][i] = hy[j][i] + ry[j][i] * cell_force(1, i, j, ffy.data(), rho.data());
      }
  }
  fill_velocity_ghosts();

  // Rotational pressure correction (Timmermans, Minev & Van De Vosse 1996): p -= chi mu div(v*).
  // With the projection's dt/rho this makes the pressure step the Cahouet-Chabard approximation of
  // the Stokes Schur complement, so viscous-dominated regions converge in a few steps, not thousands.
  const double chi = settings_.numerics.rotational_coefficient;
  if (settings_.numerics.pressure_coupling == PressureCoupling::projection && chi > 0.0) {
    {
      ConstFieldArray mu = local_read(grid_, *mu_);
      FieldArray p(grid_.field_dm(), p_->global());
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          p[j][i] -= chi * local_min_viscosity(mu.data(), i, j) * divergence_before_[size_t(j - b.ys) * b.xm + (i - b.xs)];
    }
    fill_scalar_ghosts(*p_);
    compute_face_forces();
  }
  return iterations;
}

// ---------------------------------------------------------------------------------------------

std::vector<Field*> FlowSolver::state_fields() {
  std::vector<Field*> f{vel_[0].get(), vel_[1].get(), face_[0].get(), face_[1].get(),
                        face_force_[0].get(), face_force_[1].get(), p_.get()};
  if (cell_force_[0]) f.insert(f.end(), {cell_force_[0].get(), cell_force_[1].get()});
  // u^{n-1}, so that a step taken again extrapolates from the same two states.
  if (settings_.numerics.look_ahead_viscosity) f.insert(f.end(), {vel_old_[0].get(), vel_old_[1].get()});
  if (solve_region_) f.push_back(&solve_region_->cells());
  return f;
}

// The velocity extrapolated to the end of the step, u^n + ratio (u^n - u^{n-1}) with ratio =
// dt / dt_previous (on entry vel_old_ still holds u^{n-1}).
void FlowSolver::extrapolate_velocity(double ratio) {
  for (int a = 0; a < 2; ++a) vel_ahead_[a]->combine(-ratio, *vel_old_[a], 1.0 + ratio, *vel_[a]);
}

// Properties of the first outer iteration under numerics.first_viscosity = "look_ahead": each cell
// and face takes the larger of its viscosities from u^n and from the extrapolated velocity. A region
// coming to rest gets its high plastic viscosity one Picard iteration sooner. One starting to move
// keeps that of u^n: a viscosity taken from a rate that grows ahead of the solution falls ahead of
// it too, and where the yield stress is about zero (a fringe of soil) that feedback runs away
// (docs/method.md).
void FlowSolver::update_properties_ahead() {
  update_properties();
  mu_now_->copy_from(*mu_);
  for (int a = 0; a < 2; ++a) face_mu_now_[a]->copy_from(*face_mu_[a]);
  for (int a = 0; a < 2; ++a) std::swap(vel_[a], vel_ahead_[a]);  // stands in while properties are computed
  update_properties();
  for (int a = 0; a < 2; ++a) std::swap(vel_[a], vel_ahead_[a]);
  mu_->max_with(*mu_now_);
  for (int a = 0; a < 2; ++a) face_mu_[a]->max_with(*face_mu_now_[a]);
}

// Properties of an outer iteration after the first under numerics.viscosity_pressure =
// "mean_of_last_two": the yield stress from the mean of the pressures of the last two iterations. In a
// cell far stiffer than its neighbours (the thin tip of a pile) the pressure is weakly tied to them
// and the Picard loop can settle into a two-iteration cycle: stiff, its pressure falls below zero;
// without yield stress, its pressure rises again. Two iterations per step then end every step on the
// soft half, and the floor under the cell loses its friction. The mean cancels the cycle and is the
// pressure itself once the loop converges.
void FlowSolver::update_properties_at_mean_pressure() {
  p_mean_->combine(0.5, *p_, 0.5, *p_last_iterate_);
  std::swap(p_, p_mean_);  // stands in while properties are computed
  update_properties();
  std::swap(p_, p_mean_);
}

void FlowSolver::save_state() {
  saved_.save(state_fields());
  saved_dt_ = dt_;
}
void FlowSolver::restore_state() {
  saved_.restore(state_fields());
  dt_ = saved_dt_;
}

StepReport FlowSolver::step(double dt) {
  const double dt_previous = dt_;
  dt_ = dt;
  StepReport report;
  const bool look_ahead = settings_.numerics.look_ahead_viscosity && dt_previous > 0.0;
  if (look_ahead) extrapolate_velocity(dt / dt_previous);
  for (int a = 0; a < 2; ++a) {
    vel_old_[a]->copy_from(*vel_[a]);
    face_old_[a]->copy_from(*face_[a]);
  }
  const auto& num = settings_.numerics;
  Vec u_start[2];
  for (int a = 0; a < 2; ++a) VecDuplicate(vel_[a]->global(), &u_start[a]);
  for (int outer = 0; outer < num.outer_iterations; ++outer) {
    for (int a = 0; a < 2; ++a) VecCopy(vel_[a]->global(), u_start[a]);
    if (outer == 0 && look_ahead) update_properties_ahead();
    else if (outer > 0 && num.mean_viscosity_pressure) update_properties_at_mean_pressure();
    else update_properties();
    if (num.mean_viscosity_pressure) p_last_iterate_->copy_from(*p_);
    assemble_momentum(dt);
    if (num.pressure_coupling == PressureCoupling::coupled) {
      report.pressure_iterations += solve_coupled();
      ++report.pressure_solves;
    } else {
    const bool projection = num.pressure_coupling == PressureCoupling::projection;
    if (num.momentum_predictor || projection) report.momentum_iterations += solve_momentum();
    compute_hbya();
    // The projection's pressure operator has coefficients dt / rho_f, which the outer iterations do
    // not change: one assembly and one preconditioner set-up per step. PISO's hold 1 / a_P.
    if (!projection || outer == 0) assemble_pressure_matrix(dt);
    // The projection is exact in one solve; PISO repeats the correction with updated neighbours.
    const int correctors = projection ? 1 : num.pressure_correctors;
    for (int corr = 0; corr < correctors; ++corr) {
      if (corr > 0) compute_hbya();
      report.pressure_iterations += solve_pressure(dt);
      ++report.pressure_solves;
    }
    }
    ++report.outer_iterations;
    // Convergence of the outer loop: largest velocity change relative to the largest velocity.
    double change = 0.0, scale = 0.0;
    for (int a = 0; a < 2; ++a) {
      double nv;
      VecNorm(vel_[a]->global(), NORM_INFINITY, &nv);
      VecAXPY(u_start[a], -1.0, vel_[a]->global());
      double nd;
      VecNorm(u_start[a], NORM_INFINITY, &nd);
      change = std::max(change, nd);
      scale = std::max(scale, nv);
    }
    report.velocity_change = scale > 0.0 ? change / scale : change;
    if (report.velocity_change < num.outer_tolerance) break;
  }
  for (int a = 0; a < 2; ++a) VecDestroy(&u_start[a]);
  return report;
}

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
      co = std::max(co, (std::abs(fx[j][i]) + std::abs(fx[j][i - 1])) * 0.5 * dt / grid_.dx(i) +
                            (std::abs(fy[j][i]) + std::abs(fy[j - 1][i])) * 0.5 * dt / grid_.dy(j));
    }
  return mpi_max(grid_.comm(), co);
}

double FlowSolver::max_speed() const {
  double s = 0.0;
  for (int a = 0; a < 2; ++a) {
    double n;
    VecNorm(vel_[a]->global(), NORM_INFINITY, &n);
    s = std::max(s, n);
  }
  return s;
}

FlowSolver::FastestCell FlowSolver::fastest_cell() const {
  const auto& b = grid_.owned();
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  FastestCell f;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const double s = std::hypot(u[j][i], v[j][i]);
      if (!(s <= f.speed)) f = {s, grid_.xc(i), grid_.yc(j)};  // NaN wins, so it is found
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

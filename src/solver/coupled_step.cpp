// The coupled velocity-pressure solve of FlowSolver: momentum and continuity of one outer iteration
// as one linear system in (u, v, p), or (u, v, w, p) on a mesh of layers, so that no splitting error decides how a face responds to a
// pressure jump. Faces carry Rhie-Chow fluxes with the mobility V/a_P (harmonic between the two
// cells): where viscosity holds a cell, its faces barely respond to pressure, so a rigid block next
// to air stays rigid; solved together with momentum, this small mobility cannot overshoot the way it
// does in a segregated (SIMPLE/PISO) pressure step.
#include <algorithm>
#include <cmath>
#include <optional>

#include "mesh/axis_views.hpp"
#include "mesh/cell_unknowns.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/obstacles.hpp"
#include "operators/face_interpolation.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

void FlowSolver::create_coupled_system() {
  MPI_Comm comm = grid_.comm();
  const int unknowns = dimension_ + 1;  // (u, v, p), or (u, v, w, p) on a mesh of layers
  PetscInt m, n, p;
  const PetscInt *lx, *ly, *lz;
  PetscCallAbort(comm, DMDAGetInfo(grid_.field_dm(), nullptr, nullptr, nullptr, nullptr, &m, &n, &p, nullptr,
                                   nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCallAbort(comm, DMDAGetOwnershipRanges(grid_.field_dm(), &lx, &ly, &lz));
  if (dimension_ == 3)
    PetscCallAbort(comm, DMDACreate3d(comm, grid_.matrix_x_sides(), DM_BOUNDARY_NONE, DM_BOUNDARY_NONE,
                                      DMDA_STENCIL_STAR, grid_.nx(), grid_.ny(), grid_.nz(), m, n, p, unknowns, 1, lx,
                                      ly, lz, coupled_dm_.put()));
  else
    PetscCallAbort(comm, DMDACreate2d(comm, grid_.matrix_x_sides(), DM_BOUNDARY_NONE, DMDA_STENCIL_STAR, grid_.nx(),
                                      grid_.ny(), m, n, unknowns, 1, lx, ly, coupled_dm_.put()));
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
  for (int a = 0; a < dimension_; ++a) {
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

// Rhie-Chow mobility of the face between (i, j, k) and its neighbour (in, jn, kn): harmonic mean of V/a_P.
double FlowSolver::coupled_mobility(VolumeView rau, int i, int j, int k, int in, int jn, int kn) const {
  return face_mean(FaceViscosity::harmonic, rau[k][j][i], rau[kn][jn][in]);
}

// Where the coupled system's atmosphere pressure of the face of (i, j, k) on side s is kept in
// solved_boundary_pressure_[s]: by the face's place on the side, (k, j) on west and east, (k, i) on
// south and north, (j, i) on front and back; on a planar mesh j or i.
size_t FlowSolver::boundary_face_index(Side s, int i, int j, int k) const {
  switch (normal_axis(s)) {
    case 0: return size_t(k) * grid_.ny() + j;
    case 1: return size_t(k) * grid_.nx() + i;
    default: return size_t(j) * grid_.nx() + i;
  }
}

// Balanced cell force rho_P mean(f_face / rho_face) from the current pressure, kept for the lagged
// part of the Rhie-Chow flux (which would otherwise widen the stencil).
void FlowSolver::store_cell_forces() {
  compute_face_forces();
  const auto& b = grid_.owned();
  const ConstFieldArray rho_array = local_read(grid_, *rho_);
  const AxisViews ff(grid_, face_force_);
  for (int c = 0; c < dimension_; ++c) {
    FieldArray fc(grid_.field_dm(), cell_force_[c]->global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          fc.volume()[k][j][i] = cell_force(c, i, j, k, ff.view[c], rho_array.volume());
  }
  for (int c = 0; c < dimension_; ++c) cell_force_[c]->scatter_to_local();
}

// The Rhie-Chow mobilities V / a_P per component, with ghosts.
void FlowSolver::compute_mobilities() {
  const auto& b = grid_.owned();
  for (int c = 0; c < dimension_; ++c) {
    FieldArray r(grid_.field_dm(), pressure_mobility_[c]->global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          r.volume()[k][j][i] =
              grid_.volume(i, j, k) / a_centre_[c][(size_t(k - b.zs) * b.ym + (j - b.ys)) * b.xm + (i - b.xs)];
  }
  for (int c = 0; c < dimension_; ++c) pressure_mobility_[c]->scatter_to_local();
}

// The rows of one outer iteration's coupled system, cell by cell, from the state they are linearised
// at: each row is handed to `emit(i, j, k, unknown, n, cols, vals, rhs)`. A blocked cell's faces to
// open cells are walls (mesh/obstacles.hpp): no flux, no face force, no coupling; the
// cell itself has no unknowns (outside the region, or held at rest).
class FlowSolver::CoupledRows {
 public:
  explicit CoupledRows(FlowSolver& flow)
      : f_(flow),
        grid_(flow.grid_),
        b_(flow.grid_.owned()),
        dim_(flow.dimension_),
        pressure_(flow.dimension_),
        g_(flow.settings_.gravity),
        rho_array_(local_read(grid_, *flow.rho_)),
        p_array_(local_read(grid_, *flow.p_)),
        rho_(rho_array_.volume()),
        p_now_(p_array_.volume()),
        vel_(grid_, flow.vel_),
        face_vel_(grid_, flow.face_),
        mobility_(grid_, flow.pressure_mobility_),
        cell_force_(grid_, flow.cell_force_),
        source_(grid_, flow.face_source_, flow.has_face_source() ? flow.dimension_ : 0),
        mask_(flow.grid_, flow.blocked_) {}

  double density(int i, int j, int k) const { return rho_[k][j][i]; }

  // The rows of cell (i, j, k): held at rest if blocked, else its momentum rows, one per component,
  // and its continuity row.
  template <class Emit>
  void cell(int i, int j, int k, Emit&& emit) {
    if (is_blocked(mask_.data(), i, j, k)) {  // at rest, its pressure kept
      const double one = 1.0;
      for (int unknown = 0; unknown <= pressure_; ++unknown) {
        const MatStencil row{k, j, i, unknown};
        emit(i, j, k, unknown, 1, &row, &one, unknown == pressure_ ? p_now_[k][j][i] : 0.0);
      }
      return;
    }
    for (int c = 0; c < dim_; ++c) momentum(i, j, k, c, emit);
    continuity(i, j, k, emit);
  }

 private:
  bool open_neighbour(int in, int jn, int kn) const {
    return !grid_.outside(in, jn, kn) && !is_blocked(mask_.data(), in, jn, kn);
  }

  // The pressure pb of the atmosphere at the boundary face fg of (i, j, k), recorded as the system
  // took it; false where the side is a wall.
  bool boundary_pressure(const FaceGeometry& fg, int i, int j, int k, double& pb) {
    if (boundary(f_.settings_.boundaries, fg.side).kind != BoundaryKind::atmosphere) return false;
    pb = f_.atmosphere_face_pressure(fg.side, i, j, k, rho_, vel_.view, face_vel_.view);
    f_.solved_boundary_pressure_[static_cast<int>(fg.side)][f_.boundary_face_index(fg.side, i, j, k)] = pb;
    return true;
  }

  // The distance between the centres of (i, j, k) and its neighbour across fg.
  double centre_distance(const FaceGeometry& fg, int i, int j, int k) const {
    return std::abs(grid_.centre(fg.axis, index_along(fg.axis, i + fg.di, j + fg.dj, k + fg.dk)) -
                    grid_.centre(fg.axis, index_along(fg.axis, i, j, k)));
  }

  // Momentum row of component c: a_P v_P - sum a_nb v_nb - V f_cell(p) = source.
  template <class Emit>
  void momentum(int i, int j, int k, int c, Emit&& emit) {
    const size_t n = (size_t(k - b_.zs) * b_.ym + (j - b_.ys)) * b_.xm + (i - b_.xs);
    const double Vol = grid_.volume(i, j, k), rhoP = rho_[k][j][i];
    const MatStencil row{k, j, i, c};
    MatStencil cols[10];  // the cell, six neighbours, two pressures and its own
    double vals[10];
    int m = 0;
    cols[m] = row;
    vals[m++] = f_.a_centre_[c][n];
    for (const FaceGeometry& fg : cell_faces(dim_)) {
      const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
      if (!open_neighbour(in, jn, kn)) continue;
      cols[m] = MatStencil{kn, jn, in, c};
      vals[m++] = -f_.a_neighbour_[&fg - box_faces][n];
    }
    double r = f_.source_[c][n];
    double p_centre = 0.0;
    for (int s : {1, -1}) {  // high then low face along c
      const FaceGeometry& fg = face_along(c, s);
      const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
      if (is_blocked(mask_.data(), in, jn, kn)) continue;  // an obstacle's wall carries no face force
      if (grid_.outside(in, jn, kn)) {
        const double d = 0.5 * grid_.width(c, index_along(c, i, j, k));
        double pb;
        if (!boundary_pressure(fg, i, j, k, pb)) continue;  // walls carry no face force
        // -V/2 f_b with f_b = -s (p_b - p_P)/d + rho_P g_c: p_b enters like a neighbour pressure.
        const double w = Vol / (2 * d);
        p_centre += -s * w;
        r += -s * w * pb + 0.5 * Vol * rhoP * g_[c];
        continue;
      }
      const double d = centre_distance(fg, i, j, k);
      const double rho_f = 0.5 * (rhoP + rho_[kn][jn][in]);
      const double w = Vol * rhoP / (2 * rho_f * d);  // -V rho_P/(2 rho_f) * (-s (p_N - p_P)/d)
      cols[m] = MatStencil{kn, jn, in, pressure_};
      vals[m++] = s * w;
      p_centre += -s * w;
      const double surface_force = face_source_on(source_.view, i, j, k, fg);
      r += 0.5 * Vol * rhoP * (g_[c] - f_.ambient_weight(c) / rho_f + surface_force / rho_f);
    }
    cols[m] = MatStencil{k, j, i, pressure_};
    vals[m++] = p_centre;
    emit(i, j, k, c, m, cols, vals, r);
  }

  // Continuity row: sum_f s A U_f = 0, U_f = mean(v_n) + m_f (f_f(p) - mean(f_cell)_lagged).
  template <class Emit>
  void continuity(int i, int j, int k, Emit&& emit) {
    const double rhoP = rho_[k][j][i];
    const MatStencil row{k, j, i, pressure_};
    MatStencil cols[16];
    double vals[16];
    int m = 0;
    double u_centre[3] = {0.0, 0.0, 0.0}, p_centre = 0.0, r = 0.0;
    for (const FaceGeometry& fg : cell_faces(dim_)) {
      const int axis = fg.axis;
      const int s = fg.sign > 0 ? 1 : -1;
      const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
      const VolumeView rau = mobility_.view[axis], fcell = cell_force_.view[axis];
      const double area = grid_.face_area(axis, i, j, k, s);
      if (is_blocked(mask_.data(), in, jn, kn)) continue;  // no flux through an obstacle's wall
      if (grid_.outside(in, jn, kn)) {
        const double d = 0.5 * grid_.width(axis, index_along(axis, i, j, k));
        double pb;
        if (!boundary_pressure(fg, i, j, k, pb)) {  // a wall's flux is zero, an inlet's given
          r -= s * area * imposed_normal_velocity(boundary(f_.settings_.boundaries, fg.side), grid_, fg.side, i, j, k);
          continue;
        }
        const double mob = rau[k][j][i];
        u_centre[axis] += s * area;
        p_centre += mob * area / d;
        r += mob * area / d * pb - s * area * mob * rhoP * g_[axis] + s * area * mob * fcell[k][j][i];
        continue;
      }
      const double d = centre_distance(fg, i, j, k);
      const double mob = f_.coupled_mobility(rau, i, j, k, in, jn, kn);
      const double rho_f = 0.5 * (rhoP + rho_[kn][jn][in]);
      u_centre[axis] += 0.5 * s * area;
      cols[m] = MatStencil{kn, jn, in, axis};
      vals[m++] = 0.5 * s * area;
      p_centre += mob * area / d;
      cols[m] = MatStencil{kn, jn, in, pressure_};
      vals[m++] = -mob * area / d;
      const double surface_force = face_source_on(source_.view, i, j, k, fg);
      r += -s * area * mob * rho_f * g_[axis] + s * area * mob * f_.ambient_weight(axis) +
           s * area * mob * 0.5 * (fcell[k][j][i] + fcell[kn][jn][in]) - s * area * mob * surface_force;
    }
    for (int c = 0; c < dim_; ++c) {
      cols[m] = MatStencil{k, j, i, c};
      vals[m++] = u_centre[c];
    }
    cols[m] = row;
    vals[m++] = p_centre;
    if (f_.pins_pressure_level_ && i == f_.pin_i_ && j == f_.pin_j_ && k == f_.pin_k_) {
      // A closed domain's continuity rows sum to zero (every face's flux enters two of them with
      // opposite signs), so one of them is implied by the others; this cell's holds the pressure
      // level at the last iterate's instead, scaled like the row it replaces.
      std::fill(vals, vals + m - 1, 0.0);
      r = p_centre * p_now_[k][j][i];
    }
    emit(i, j, k, pressure_, m, cols, vals, r);
  }

  FlowSolver& f_;
  const Grid& grid_;
  const CellBox& b_;
  const int dim_, pressure_;  // the pressure's unknown follows the velocity's components
  const std::array<double, 3>& g_;
  const ConstFieldArray rho_array_, p_array_;
  const VolumeView rho_, p_now_;
  const AxisViews vel_, face_vel_, mobility_, cell_force_, source_;
  const BlockedView mask_;
};

// The coupled rows of velocity and pressure, over the air band's region or the whole domain.
void FlowSolver::fill_coupled_rows() {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  const int pressure = dimension_;
  for (Side side : sides_of_dimension(dimension_)) {  // NaN: a face the system below does not hold
    const int axis = normal_axis(side);             // (outside the air band's region)
    const size_t faces = axis == 0 ? size_t(ny) * nz : (axis == 1 ? size_t(nx) * nz : size_t(nx) * ny);
    solved_boundary_pressure_[static_cast<int>(side)].assign(faces, std::nan(""));
  }
  CoupledRows rows(*this);
  if (solve_region_) {
    // Only the region's rows; outside, air at rest under the pressure of the air column above it.
    const long region_cells = solve_region_->prepare();
    // Without an open side nothing else fixes the pressure's level, unless the region leaves out some
    // cells, whose air at rest under a zero top then holds it. Blocked cells are never in the region:
    // it covers every open cell if it holds as many.
    pins_pressure_level_ = !has_pressure_boundary_ && region_cells == (blocked_ ? open_cells_ : grid_.cell_count());
    if (region_cells == 0) return;
    auto outside = [&](int i, int j, int k, int unknown) {
      return unknown == pressure ? pressure_at_rest(rows.density(i, j, k), j) : 0.0;
    };
    SolveRegion::RowWriter region_rows(*solve_region_);
    auto emit = [&](int i, int j, int k, int unknown, int n, const MatStencil* cols, const double* vals, double r) {
      region_rows.set(i, j, k, unknown, n, cols, vals, r, outside);
    };
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          if (region_rows.inside(i, j, k)) rows.cell(i, j, k, emit);
  } else {
    pins_pressure_level_ = !has_pressure_boundary_;
    {
      const CellUnknowns rhs(grid_.comm(), coupled_rhs_, b, dimension_ + 1);
      auto emit = [&](int i, int j, int k, int unknown, int n, const MatStencil* cols, const double* vals, double r) {
        const MatStencil row{k, j, i, unknown};
        PetscCallAbort(PETSC_COMM_SELF, MatSetValuesStencil(coupled_matrix_, 1, &row, n, cols, vals, INSERT_VALUES));
        rhs(i, j, k, unknown) = r;
      };
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i) rows.cell(i, j, k, emit);
    }
    PetscCallAbort(grid_.comm(), MatAssemblyBegin(coupled_matrix_, MAT_FINAL_ASSEMBLY));
    PetscCallAbort(grid_.comm(), MatAssemblyEnd(coupled_matrix_, MAT_FINAL_ASSEMBLY));
  }
}

// Solves the coupled rows from the current state and takes their solution as the state; the air
// outside a band's region at rest and hydrostatic. Returns the iterations.
int FlowSolver::solve_coupled_rows(bool by_first_factorisation) {
  const auto& b = grid_.owned();
  const int pressure = dimension_;
  // Initial guess: the current state; outside a band's region, air at rest under the pressure of the
  // air column above it.
  {
    const CellUnknowns x(grid_.comm(), coupled_solution_, b, dimension_ + 1);
    const AxisViews vel(grid_, vel_, dimension_, true);
    const ConstFieldArray p(grid_.field_dm(), p_->global()), rho(grid_.field_dm(), rho_->global());
    std::optional<ConstFieldArray> inside;
    if (solve_region_) inside.emplace(grid_.field_dm(), solve_region_->cells().global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const bool at_rest = inside && inside->volume()[k][j][i] == 0.0;
          for (int c = 0; c < dimension_; ++c) x(i, j, k, c) = at_rest ? 0.0 : vel.view[c][k][j][i];
          x(i, j, k, pressure) = at_rest ? pressure_at_rest(rho.volume()[k][j][i], j) : p.volume()[k][j][i];
        }
  }
  int iterations = 0;
  if (solve_region_) {
    if (solve_region_->cell_count() > 0)
      iterations = by_first_factorisation ? solve_region_->solve_by_last_factorisation(
                                                coupled_solution_, settings_.numerics.krylov_iterations)
                                          : solve_region_->solve(coupled_solution_);
  } else if (by_first_factorisation) {
    iterations = coupled_solver_->solve_by_last_factorisation(coupled_rhs_, coupled_solution_,
                                                               settings_.numerics.krylov_iterations);
  } else {
    coupled_solver_->set_operator(coupled_matrix_);
    iterations = coupled_solver_->solve(coupled_rhs_, coupled_solution_);
  }
  {
    const CellUnknowns x(grid_.comm(), coupled_solution_, b, dimension_ + 1);
    std::optional<FieldArray> vel[3];
    for (int c = 0; c < dimension_; ++c) vel[c].emplace(grid_.field_dm(), vel_[c]->global());
    FieldArray p(grid_.field_dm(), p_->global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          for (int c = 0; c < dimension_; ++c) vel[c]->volume()[k][j][i] = x(i, j, k, c);
          p.volume()[k][j][i] = x(i, j, k, pressure);
        }
  }
  return iterations;
}

void FlowSolver::update_coupled_face_velocities() {
  const auto& b = grid_.owned();
  const auto& g = settings_.gravity;
  // Face velocities with exactly the flux of the continuity rows (divergence-free to the tolerance).
  // An atmosphere face keeps the pressure the rows were built with: with total pressure, inflow
  // enters at p0 - rho |v_P|^2 / 2, and v_P has just changed. Taken anew, it gave an open top under
  // a falling water column a flux of its own, and the water's volume grew by 2e-5.
  compute_face_forces();
  {
    const ConstFieldArray p_array = local_read(grid_, *p_), rho_array = local_read(grid_, *rho_);
    const VolumeView p = p_array.volume(), rho = rho_array.volume();
    for (Side side : sides_of_dimension(dimension_)) {
      if (!grid_.owns_boundary(side)) continue;
      const FaceGeometry& fg = face_on(side);
      const int axis = fg.axis;
      const auto& solved = solved_boundary_pressure_[static_cast<int>(side)];
      FieldArray ff_array = local_array(grid_, *face_force_[axis]);
      double*** ff = ff_array.volume();
      // The owned cells next to the side.
      int lo[3] = {b.xs, b.ys, b.zs}, hi[3] = {b.xe(), b.ye(), b.ze()};
      if (fg.sign < 0) hi[axis] = lo[axis] + 1;
      else lo[axis] = hi[axis] - 1;
      const bool low = fg.sign < 0;
      for (int k = lo[2]; k < hi[2]; ++k)
        for (int j = lo[1]; j < hi[1]; ++j)
          for (int i = lo[0]; i < hi[0]; ++i) {
            const double pb = solved[boundary_face_index(side, i, j, k)];
            if (std::isnan(pb)) continue;
            const double d = 0.5 * grid_.width(axis, index_along(axis, i, j, k));
            ff[k - (low && axis == 2)][j - (low && axis == 1)][i - (low && axis == 0)] =
                -fg.sign * (pb - p[k][j][i]) / d + rho[k][j][i] * g[axis];
          }
    }
  }
  const AxisViews vel(grid_, vel_), mobility(grid_, pressure_mobility_), fcell(grid_, cell_force_),
      ff(grid_, face_force_);
  const BlockedView mask(grid_, blocked_);
  fill_owned_faces_any(
      grid_, per_axis(face_),
      [&](int axis, int i, int j, int k) {
        const VolumeView q = vel.view[axis], fc = fcell.view[axis];
        const int in = i + (axis == 0), jn = j + (axis == 1), kn = k + (axis == 2);
        return 0.5 * (q[k][j][i] + q[kn][jn][in]) + coupled_mobility(mobility.view[axis], i, j, k, in, jn, kn) *
                                                        (ff.view[axis][k][j][i] - 0.5 * (fc[k][j][i] + fc[kn][jn][in]));
      },
      [&](int axis, int i, int j, int k, int sign) {
        const FaceGeometry& fg = face_along(axis, sign);
        // An obstacle's wall, a side of an obstacle's cell, or a wall side: no flux; an inlet's is given.
        if (!grid_.outside(i + fg.di, j + fg.dj, k + fg.dk) || is_blocked(mask.data(), i, j, k)) return 0.0;
        const auto& bc = boundary(settings_.boundaries, fg.side);
        if (bc.kind != BoundaryKind::atmosphere) return imposed_normal_velocity(bc, grid_, fg.side, i, j, k);
        return vel.view[axis][k][j][i] +
               mobility.view[axis][k][j][i] * (on_face(ff.view, i, j, k, fg) - fcell.view[axis][k][j][i]);
      },
      mask.data());
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

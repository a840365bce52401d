#include "solver/flow_solver.hpp"

#include "mesh/face_loop.hpp"
#include "mesh/axis_views.hpp"
#include "models/mixture/carried_momentum.hpp"
#include "solver/cell_faces.hpp"
#include "mesh/copied_ghosts.hpp"
#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "mesh/obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "operators/face_interpolation.hpp"
#include "solver/velocity_ghosts.hpp"

namespace granflow {

namespace {

std::unique_ptr<Field> make_field(const Grid& g) { return std::make_unique<Field>(g); }

}  // namespace

FlowSolver::FlowSolver(const Grid& grid, const FlowSettings& settings)
    : grid_(grid), settings_(settings), dimension_(grid.dimension()) {
  for (int a = 0; a < dimension_; ++a) {
    vel_[a] = make_field(grid);
    vel_old_[a] = make_field(grid);
    outer_start_[a] = make_field(grid);
    face_[a] = make_field(grid);
    face_old_[a] = make_field(grid);
    face_force_[a] = make_field(grid);
    pressure_mobility_[a] = make_field(grid);
    vel_[a]->set(0.0);
    face_[a]->set(0.0);
    face_force_[a]->set(0.0);
  }
  p_ = make_field(grid);
  rho_ = make_field(grid);
  mu_ = make_field(grid);
  p_->set(0.0);
  if (settings_.numerics.look_ahead_viscosity) {
    for (int a = 0; a < dimension_; ++a) {
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
  for (int a = 0; a < dimension_; ++a) {
    face_mu_[a] = make_field(grid);
    face_mu_[a]->set(1.0);
  }

  const auto& box = grid.owned();
  const size_t n = size_t(box.xm) * box.ym * box.zm;
  for (const auto& f : cell_faces(dimension_)) a_neighbour_[&f - box_faces].assign(n, 0.0);
  for (int a = 0; a < dimension_; ++a) {
    a_centre_[a].assign(n, 0.0);
    source_[a].assign(n, 0.0);
  }

  for (Side s : sides_of_dimension(dimension_))
    if (boundary(settings.boundaries, s).kind == BoundaryKind::atmosphere) has_pressure_boundary_ = true;
  impose_inlet_face_velocities();  // an inlet's faces carry its inflow from the start (a schedule's: Simulation)
  shared_momentum_matrix_ = momentum_matrix_shared(settings, grid.axisymmetric(), dimension_);

  MPI_Comm comm = grid.comm();
  // The segregated steps' matrices, solvers and fields (the second momentum matrix only where u and v
  // do not share one); the coupled solve makes its own system
  // (coupled_step.cpp), so it is spared their memory.
  const bool segregated = settings.numerics.pressure_coupling != PressureCoupling::coupled;
  if (segregated) {
    for (int a = 0; a < dimension_; ++a) {
      velocity_without_pressure_[a] = make_field(grid);
      old_time_share_[a] = make_field(grid);
      old_time_share_[a]->set(0.0);  // stays zero under the projection coupling
      if (a > 0 && shared_momentum_matrix_) continue;
      PetscCallAbort(comm, DMCreateMatrix(grid.matrix_dm(), momentum_matrix_[a].put()));
      static const char* const prefixes[3] = {"momentum_x", "momentum_y", "momentum_z"};
      momentum_solver_[a] = std::make_unique<LinearSolver>(comm, prefixes[a], settings.momentum_solver, dimension_);
    }
    PetscCallAbort(comm, DMCreateMatrix(grid.matrix_dm(), pressure_matrix_.put()));
    pressure_solver_ = std::make_unique<LinearSolver>(comm, "pressure", settings.pressure_solver, dimension_);
    PetscCallAbort(comm, DMCreateGlobalVector(grid.field_dm(), rhs_.put()));
  }

  if (!segregated) create_coupled_system();
  pin_j_ = grid.ny() - 1;  // the top-left cell, and every cell open, until set_blocked says otherwise
  open_cells_ = grid.cell_count();
  update_boundary_heads();
  if (segregated && !has_pressure_boundary_) {
    PetscCallAbort(comm, MatNullSpaceCreate(comm, PETSC_TRUE, 0, nullptr, pressure_null_space_.put()));
    PetscCallAbort(comm, MatSetNullSpace(pressure_matrix_, pressure_null_space_));
  }
}

void FlowSolver::enable_body_force() {
  for (int a = 0; a < dimension_; ++a)
    if (!body_force_[a]) {
      body_force_[a] = make_field(grid_);
      body_force_[a]->set(0.0);
    }
}

void FlowSolver::enable_face_source() {
  for (int a = 0; a < dimension_; ++a)
    if (!face_source_[a]) {
      face_source_[a] = make_field(grid_);
      face_source_[a]->set(0.0);
    }
}

FlowSolver::~FlowSolver() = default;

// ---------------------------------------------------------------------------------------------
// Ghosts: interior ghosts come from neighbouring ranks; ghosts outside the domain encode the
// boundary conditions (mirror images), so that stencils near walls need no special cases.

void FlowSolver::set_blocked(const Field* mask) {
  blocked_ = mask;
  if (!mask) {  // every cell open; the closed domain's level held in the top-left cell, as constructed
    open_cells_ = grid_.cell_count();
    pin_i_ = pin_k_ = 0;
    pin_j_ = grid_.ny() - 1;
    return;
  }
  if (solve_region_) solve_region_->set_blocked(mask);
  // The closed domain's pinned row: the open cell nearest the top-left (front) corner, layer by layer
  // of the top row first, then row by row down.
  const long nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  long key = grid_.cell_count();
  open_cells_ = 0;
  {
    BlockedView m(grid_, blocked_);
    const auto& b = grid_.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          if (!is_blocked(m.data(), i, j, k)) {
            key = std::min(key, ((ny - 1 - j) * nz + k) * nx + i);
            ++open_cells_;
          }
  }
  MPI_Allreduce(MPI_IN_PLACE, &key, 1, MPI_LONG, MPI_MIN, grid_.comm());
  MPI_Allreduce(MPI_IN_PLACE, &open_cells_, 1, MPI_LONG, MPI_SUM, grid_.comm());
  pin_i_ = int(key % nx);
  pin_k_ = int(key / nx % nz);
  pin_j_ = int(ny - 1 - key / nx / nz);
}

void FlowSolver::fill_scalar_ghosts(Field& f) { fill_copied_ghosts(grid_, blocked_, f); }

void FlowSolver::fill_velocity_ghosts() {
  for (int a = 0; a < dimension_; ++a) vel_[a]->scatter_to_local();
  std::optional<FieldArray> arrays[3];
  double*** components[3] = {};
  for (int a = 0; a < dimension_; ++a) components[a] = arrays[a].emplace(grid_.field_dm(), vel_[a]->local()).volume();
  // An obstacle's walls are static and no-slip.
  for (int a = 0; a < dimension_; ++a) mirror_into_blocked(grid_, blocked_, components[a], -1.0);
  fill_velocity_side_ghosts(grid_, settings_.boundaries, std::span<double*** const>(components, dimension_));
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
  const ConstFieldArray mu_array = local_read(grid_, *mu_);
  const VolumeView mu = mu_array.volume();
  fill_owned_faces_any(
      grid_, per_axis(face_mu_),
      [&](int axis, int i, int j, int k) {
        return face_mean(kind, mu[k][j][i], at(mu, i + (axis == 0), j + (axis == 1), k + (axis == 2)));
      },
      [&](int, int i, int j, int k, int) { return mu[k][j][i]; }, BlockedView(grid_, blocked_).data());
}

// ---------------------------------------------------------------------------------------------

std::vector<std::pair<const char*, Field*>> FlowSolver::named_state_fields() {
  std::vector<std::pair<const char*, Field*>> f{{"u", vel_[0].get()},
                                                {"v", vel_[1].get()},
                                                {"face_u", face_[0].get()},
                                                {"face_v", face_[1].get()},
                                                {"face_force_x", face_force_[0].get()},
                                                {"face_force_y", face_force_[1].get()},
                                                {"p", p_.get()}};
  if (cell_force_[0]) f.insert(f.end(), {{"cell_force_x", cell_force_[0].get()}, {"cell_force_y", cell_force_[1].get()}});
  // u^{n-1}, so that a step taken again extrapolates from the same two states.
  if (settings_.numerics.look_ahead_viscosity)
    f.insert(f.end(), {{"u_previous", vel_old_[0].get()}, {"v_previous", vel_old_[1].get()}});
  if (dimension_ == 3) {  // the third component's, after the planar ones (whose order checkpoints keep)
    f.insert(f.end(), {{"w", vel_[2].get()}, {"face_w", face_[2].get()}, {"face_force_z", face_force_[2].get()}});
    if (settings_.numerics.look_ahead_viscosity) f.emplace_back("w_previous", vel_old_[2].get());
    if (cell_force_[2]) f.emplace_back("cell_force_z", cell_force_[2].get());
  }
  if (solve_region_) f.emplace_back("solve_region", &solve_region_->cells());
  // Only where it is read: a run that keeps the velocity at the density's jumps restarts from the
  // checkpoints written before the carried density was kept.
  if (carried_density_ && settings_.numerics.density_jump_keeps_kinetic_energy)
    f.emplace_back("carried_density", carried_density_.get());
  return f;
}

std::vector<Field*> FlowSolver::state_fields() {
  std::vector<Field*> fields;
  for (const auto& [name, f] : named_state_fields()) fields.push_back(f);
  return fields;
}

std::string FlowSolver::checkpoint_field_names() {
  std::string names;
  for (const auto& [name, f] : named_state_fields()) {
    if (!names.empty()) names += ' ';
    names += name;
  }
  return names;
}

// The velocity extrapolated to the end of the step, u^n + ratio (u^n - u^{n-1}) with ratio =
// dt / dt_previous (on entry vel_old_ still holds u^{n-1}).
void FlowSolver::extrapolate_velocity(double ratio) {
  for (int a = 0; a < dimension_; ++a) vel_ahead_[a]->combine(-ratio, *vel_old_[a], 1.0 + ratio, *vel_[a]);
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
  for (int a = 0; a < dimension_; ++a) face_mu_now_[a]->copy_from(*face_mu_[a]);
  for (int a = 0; a < dimension_; ++a) std::swap(vel_[a], vel_ahead_[a]);  // stands in while properties are computed
  update_properties();
  for (int a = 0; a < dimension_; ++a) std::swap(vel_[a], vel_ahead_[a]);
  mu_->max_with(*mu_now_);
  for (int a = 0; a < dimension_; ++a) face_mu_[a]->max_with(*face_mu_now_[a]);
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

void FlowSolver::enable_mass_transport() {
  start_density_ = make_field(grid_);
  start_density_->copy_from(*rho_);
  carried_density_ = make_field(grid_);  // the mixture's density, as its properties fill it (local values)
  carried_density_->copy_from(*rho_);
  carried_density_->gather_from_local();
  start_momentum_density_ = make_field(grid_);
  start_momentum_density_->copy_from(*carried_density_);
  for (int a = 0; a < dimension_; ++a) {
    mass_flux_[a] = make_field(grid_);
    mass_flux_[a]->set(0.0);
  }
}

void FlowSolver::carry_momentum_mass(double dt) {
  if (!settings_.numerics.density_jump_keeps_kinetic_energy) return;  // the step starts at the velocity
  const auto& b = grid_.owned();
  const auto faces = cell_faces(dimension_);
  {
    const ConstFieldArray rho0(grid_.field_dm(), start_density_->local());  // as the soil fills it
    const AxisViews mass_flux(grid_, mass_flux_);
    FieldArray carried(grid_.field_dm(), carried_density_->global());
    FieldArray start(grid_.field_dm(), start_momentum_density_->global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const double rho = rho0.volume()[k][j][i], V = grid_.volume(i, j, k);
          start.volume()[k][j][i] = mixture::carried_momentum_density(rho, carried.volume()[k][j][i]);
          double mass = rho * V;  // plus what flows in over the step, less what flows out
          for (const FaceGeometry& fg : faces)
            mass -= dt * fg.sign * grid_.face_area(fg.axis, i, j, k, fg.sign) * on_face(mass_flux.view, i, j, k, fg);
          carried.volume()[k][j][i] = mass / V;
        }
  }
  carried_density_->scatter_to_local();  // a snapshot or checkpoint keeps the local values
}

void FlowSolver::save_state() {
  saved_.save(state_fields());
  saved_dt_ = dt_;
}
void FlowSolver::restore_state() {
  saved_.restore(state_fields());
  clear_blocked_cells();
  dt_ = saved_dt_;
}

// An inlet of a schedule takes its velocity at time t; the velocity's ghosts follow.
bool FlowSolver::set_inflow_time(double t) {
  bool changed = false;
  for (auto& bc : settings_.boundaries) {
    if (bc.kind != BoundaryKind::inlet || bc.inflow_schedule.empty()) continue;
    const double factor = inflow_factor(bc.inflow_schedule, t);
    for (int c = 0; c < 3; ++c) bc.velocity[c] = factor * bc.inflow_velocity[c];
    changed = true;
  }
  if (changed) fill_velocity_ghosts();
  return changed;
}

// An inlet's faces hold its velocity; every other face keeps its own.
void FlowSolver::impose_inlet_face_velocities() {
  const auto& b = grid_.owned();
  const int n[3] = {grid_.nx(), grid_.ny(), grid_.nz()};
  for (Side side : sides_of_dimension(dimension_)) {
    const auto& bc = boundary(settings_.boundaries, side);
    if (bc.kind != BoundaryKind::inlet || !grid_.owns_boundary(side)) continue;
    const int axis = normal_axis(side);
    FieldArray f = local_array(grid_, *face_[axis]);  // the boundary face: index -1 or n - 1 along the axis
    int lo[3] = {b.xs, b.ys, b.zs}, hi[3] = {b.xe(), b.ye(), b.ze()};
    lo[axis] = face_on(side).sign < 0 ? -1 : n[axis] - 1;
    hi[axis] = lo[axis] + 1;
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i)
          f.volume()[k][j][i] = imposed_normal_velocity(bc, grid_, side, i, j, k);
  }
}

// Fields restored from local values (a snapshot, a checkpoint) carry the blocked cells' mirrors into
// their global vectors; a blocked cell is at rest.
void FlowSolver::clear_blocked_cells() {
  if (!blocked_) return;
  for (int a = 0; a < dimension_; ++a)
    for (auto* f : {vel_[a].get(), vel_old_[a].get()}) zero_blocked_cells(grid_, blocked_, *f);
}

StepReport FlowSolver::step(double dt) {
  const double dt_previous = dt_;
  dt_ = dt;
  StepReport report;
  const bool look_ahead = settings_.numerics.look_ahead_viscosity && dt_previous > 0.0;
  if (look_ahead) extrapolate_velocity(dt / dt_previous);
  for (int a = 0; a < dimension_; ++a) {
    vel_old_[a]->copy_from(*vel_[a]);
    face_old_[a]->copy_from(*face_[a]);
  }
  const auto& num = settings_.numerics;
  for (int outer = 0; outer < num.outer_iterations; ++outer) {
    for (int a = 0; a < dimension_; ++a) PetscCallAbort(grid_.comm(), VecCopy(vel_[a]->global(), outer_start_[a]->global()));
    if (outer == 0 && look_ahead) update_properties_ahead();
    else if (outer > 0 && num.mean_viscosity_pressure) update_properties_at_mean_pressure();
    else update_properties();
    if (num.mean_viscosity_pressure) p_last_iterate_->copy_from(*p_);
    assemble_momentum(dt);
    if (num.pressure_coupling == PressureCoupling::coupled) {
      report.pressure_iterations += solve_coupled(outer > 0 && num.reuse_first_factorisation);
      ++report.pressure_solves;
    } else {
      const bool projection = num.pressure_coupling == PressureCoupling::projection;
      if (num.momentum_predictor || projection) report.momentum_iterations += solve_momentum();
      compute_velocity_without_pressure();
      // The projection's pressure operator has coefficients dt / rho_f, which the outer iterations do
      // not change: one assembly and one preconditioner set-up per step. PISO's hold 1 / a_P.
      if (!projection || outer == 0) assemble_pressure_matrix();
      // The projection is exact in one solve; PISO repeats the correction with updated neighbours.
      const int correctors = projection ? 1 : num.pressure_correctors;
      for (int corr = 0; corr < correctors; ++corr) {
        if (corr > 0) compute_velocity_without_pressure();
        report.pressure_iterations += solve_pressure();
        ++report.pressure_solves;
      }
    }
    ++report.outer_iterations;
    // Convergence of the outer loop: largest velocity change relative to the largest velocity.
    double change = 0.0, scale = 0.0;
    for (int a = 0; a < dimension_; ++a) {
      const double nv = max_abs(grid_.comm(), vel_[a]->global());
      const Vec start = outer_start_[a]->global();
      PetscCallAbort(grid_.comm(), VecAXPY(start, -1.0, vel_[a]->global()));
      change = larger_or_nan(change, max_abs(grid_.comm(), start));  // a NaN iterate is not converged
      scale = larger_or_nan(scale, nv);
    }
    report.velocity_change = scale > 0.0 ? change / scale : change;
    if (report.velocity_change < num.outer_tolerance) break;
  }
  return report;
}

void FlowSolver::rebuild_preconditioners() {
  for (auto& s : momentum_solver_)
    if (s) s->rebuild_at_next_solve();
  if (pressure_solver_) pressure_solver_->rebuild_at_next_solve();
  if (coupled_solver_) coupled_solver_->rebuild_at_next_solve();
  if (solve_region_) solve_region_->rebuild_at_next_solve();
}

}  // namespace granflow

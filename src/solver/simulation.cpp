#include "solver/simulation.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "io/case_error.hpp"
#include "io/collective_failure.hpp"
#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "io/run_directory.hpp"
#include "mesh/obstacles.hpp"
#include "models/interface/initial_shapes.hpp"
#include "solver/case_layout.hpp"

namespace granflow {



Simulation::Simulation(MPI_Comm comm, const CaseConfig& config, std::filesystem::path output_dir)
    : config_(config), out_(std::move(output_dir)) {
  MPI_Comm_rank(comm, &rank_);
  grid_ = std::make_unique<Grid>(comm, config.mesh);
  if (config.has_obstacles()) {
    blocked_ = std::make_unique<Field>(*grid_);
    ObstacleLayout layout = lay_out_obstacles(*grid_, config, *blocked_);
    // What a checkpoint records of them: the fields of one set of obstacles are not another's state.
    obstacles_ = fmt::format(", obstacles blocking {} cells (hash {:016x})", layout.blocked_cells, layout.hash);
    blocked_on_root_ = std::move(layout.mask_on_root);
    ridges_lowered_ = granflow::ridges_lowered(layout);
    // The west wall the history's wall height is read at (on rank 0): the first column with an open cell.
    if (rank_ == 0) {
      const int nx = grid_->nx();
      wall_column_ = nx;
      for (size_t k = 0; k < blocked_on_root_.size(); ++k)
        if (blocked_on_root_[k] <= 0.5) wall_column_ = std::min(wall_column_, int(k % nx));
    }
  }
  flow_ = std::make_unique<FlowSolver>(*grid_, config.flow);
  if (flow_->set_inflow_time(inflow_time_after(config.flow.boundaries, 0.0, config.time.dt)))
    flow_->impose_inlet_face_velocities();  // the first step's sweeps carry this inflow
  flow_->set_blocked(blocked_.get());
  if (config.soil) {
    soil_ = std::make_unique<SoilPhase>(*grid_, flow_->settings(), *config.soil);
    soil_->set_blocked(blocked_.get());
    if (std::any_of(config.obstacle_friction.begin(), config.obstacle_friction.end(), [](const auto& f) { return f.has_value(); })) {
      obstacle_index_ = std::make_unique<Field>(*grid_);
      if (grid_->dimension() == 3)
        mark_obstacle_index(*grid_, interface::ShapeUnion3(config.obstacle_solids), *obstacle_index_);
      else
        mark_obstacle_index(*grid_, interface::ShapeUnion(config.obstacles), *obstacle_index_);
      soil_->set_obstacle_friction(obstacle_index_.get(), config.obstacle_friction);
    }
    soil_->initialise();
    soil_->refresh(*flow_);
    if (config.soil->surface_tension > 0.0) {
      surface_tension_ = std::make_unique<SurfaceTensionForce>(
          *grid_, config.soil->surface_tension, config.soil->contact_angle, config.flow.boundaries, blocked_.get());
      surface_tension_->fill(soil_->soil_fraction(), *flow_);
    }
    flow_->set_property_update([soil = soil_.get()](FlowSolver& f) { soil->update_properties(f); });
    if (config_.soil->rheology && config_.soil->yield_pressure == YieldPressure::face)
      flow_->set_face_viscosity_update([soil = soil_.get()](FlowSolver& f) { soil->update_face_viscosity(f); });
  } else {
    const PhaseSettings fluid = config.fluid;
    flow_->set_property_update([fluid](FlowSolver& f) {
      PetscCallAbort(f.grid().comm(), VecSet(f.density().global(), fluid.density));
      PetscCallAbort(f.grid().comm(), VecSet(f.viscosity().global(), fluid.viscosity));
    });
  }
  flow_->update_properties();
  flow_->refresh_ghosts();
  flow_->set_hydrostatic_pressure();
  flow_->update_properties();  // the granular viscosity needs the pressure
  // From the mixture's initial density: the mass the first step's momentum is carried with.
  if (soil_ && config.flow.numerics.conservative_momentum) flow_->enable_mass_transport();
  if (soil_) initial_soil_volume_ = soil_->budget(*flow_).soil_volume;
  // The budget is summed over all ranks: all stop alike. A case of no initial shapes starts empty
  // (an inlet of soil fills it).
  if (soil_ && config_.soil->has_initial_shapes() && !(initial_soil_volume_ > 0.0))
    throw no_initial_soil(config_, *grid_, blocked_ != nullptr);
  if (soil_) check_materials_hold_soil(config_, soil_->material_volumes());
  if (!out_.empty()) {
    std::string problem;
    if (rank_ == 0) {
      std::error_code ec;
      std::filesystem::create_directories(out_, ec);
      if (ec) {
        problem = fmt::format("-o {}: cannot make the output directory: {}", out_.string(), ec.message());
        std::error_code ignored;
        if (std::filesystem::is_symlink(out_, ignored))
          problem += fmt::format(" (it is a symbolic link to {}, which is not a directory)",
                                 std::filesystem::read_symlink(out_, ignored).string());
      }
      // Found now rather than at the first output, which may come after much of the run.
      if (problem.empty()) {
        const auto probe = out_ / fmt::format(".granflow_probe_{}", ::getpid());
        if (!std::ofstream(probe))
          problem = fmt::format("-o {}: cannot write into the output directory: {}", out_.string(), std::strerror(errno));
        std::filesystem::remove(probe, ec);
      }
    }
    if (auto text = first_failure(comm, problem); !text.empty()) throw CaseError(text);  // on every rank
    series_ = std::make_unique<VtkSeries>(out_, "fields");
  }
}

Simulation::~Simulation() = default;

InitialState check_initial_state(MPI_Comm comm, const CaseConfig& config) {
  const Grid grid(comm, config.mesh);
  InitialState state;
  std::unique_ptr<Field> blocked;
  if (config.has_obstacles()) {
    blocked = std::make_unique<Field>(grid);
    const ObstacleLayout layout = lay_out_obstacles(grid, config, *blocked);
    state.blocked_cells = layout.blocked_cells;
    state.ridges_lowered = ridges_lowered(layout);
  }
  if (!config.soil) return state;
  const PlacedSoil placed = initial_soil_placed(grid, config, blocked.get());
  state.soil_volume = placed.in_open_cells;
  state.soil_in_obstacles = placed.in_blocked_cells;
  if (config.soil->has_initial_shapes() && !(state.soil_volume > 0.0))
    throw no_initial_soil(config, grid, blocked != nullptr);
  if (!config.soil->materials.empty()) {  // the shares as a run lays them out
    SoilPhase soil(grid, config.flow, *config.soil);
    soil.set_blocked(blocked.get());
    soil.initialise();
    state.material_volumes = soil.material_volumes();
    check_materials_hold_soil(config, state.material_volumes);
  }
  return state;
}

double Simulation::next_output_time() const {
  double next = config_.time.end;
  if (config_.output.interval > 0.0) {
    const double k = std::floor(time_ / config_.output.interval + 1e-9) + 1.0;
    next = std::min(next, k * config_.output.interval);
  }
  for (double t : config_.output.times)
    if (t > time_ * (1 + 1e-12) + 1e-300) next = std::min(next, t);
  return next;
}

// numerics.air_band: the coupled solve covers the soil and a band of air around it. The band is
// laid anew, air_band cells wide, once the soil has come within half of that of its edge, so the
// factorisation's analysis serves several steps.
// Only soil fractions above a trace count: the geometric sweeps leave slivers of 1e-20 to 1e-16
// where a swept strip grazes the interface, there or exactly 0 by the round-off of the face
// velocities, so with any non-zero fraction counting, the region (and with it the air's flow)
// differed between rank layouts now and then. A fraction within round-off of 1e-9 is far rarer.
// A trace left outside the region is advected and conserved like any soil.
void Simulation::update_solve_region() {
  constexpr double trace_fraction = 1e-9;
  const int band = config_.flow.numerics.air_band;
  if (band == 0) return;
  // The soil was just moved by the last solve's face velocities, over its region: soil that crossed
  // its edge would cross faces that no continuity row balances, and its volume be lost. Soil in the
  // region's outermost ring (the soil widened by one cell not covered) stops the run before that.
  // The case file's rule on the band's width keeps adaptive steps within it; a fixed step may not be.
  // Before a region is laid (the first step, and that step taken again) no solve has moved the soil.
  if (flow_->solve_region_laid() && !flow_->solve_region_covers(soil_->soil_region(1, trace_fraction)))
    throw DivergenceError(fmt::format("at t = {:.6g} s the soil reached the edge of the region of the coupled solve "
                                      "in one step (numerics.air_band = {}): shorten the step (time.dt, "
                                      "time.max_dt) or widen the band", time_, band));
  if (flow_->solve_region_covers(soil_->soil_region(band - band / 2, trace_fraction))) return;
  flow_->set_solve_region(soil_->soil_region(band, trace_fraction));
}

double Simulation::courant_after(double dt) const {
  const bool soil_only = soil_ && config_.time.courant_region == CourantRegion::soil;
  return flow_->max_courant(dt, soil_only ? &soil_->soil_fraction() : nullptr);
}

double Simulation::choose_dt(double dt_previous) const {
  const auto& t = config_.time;
  // The surface tension's force is explicit: its capillary limit holds a fixed step too.
  const double capillary = surface_tension_ ? capillary_time_step() : t.max_dt;
  if (!t.adaptive) return std::min({t.dt, t.max_dt, capillary});
  const bool soil_only = soil_ && t.courant_region == CourantRegion::soil;
  const double co = flow_->max_courant(dt_previous, soil_only ? &soil_->soil_fraction() : nullptr);
  // A NaN Courant number (the flow broke down where the speed check did not see it) shrinks the step.
  double dt = std::isnan(co) ? 0.1 * dt_previous : co > 0.0 ? dt_previous * t.courant / co : dt_previous * t.max_growth;
  if (soil_) {
    const double ci = soil_->interface_courant(*flow_, dt_previous, t.interface_substeps);
    const double limit = t.interface_substeps * soil_->settings().interface_courant;
    if (std::isnan(ci)) dt = std::min(dt, 0.1 * dt_previous);
    else if (ci > 0.0) dt = std::min(dt, dt_previous * limit / ci);
  }
  dt = std::min({dt, dt_previous * t.max_growth, t.max_dt, capillary});
  return dt;
}

// One step of [VoF] Algorithm 1: the interface moved explicitly, then the flow's outer iterations,
// then the displacement carried with the new velocity. A step whose velocities come out far above
// the Courant limit it was sized for (a splash, a sudden yield) is taken again from the saved state
// with a step sized for the velocities it produced: the step size lags the flow by one step, and an
// implicit step can survive a Courant number of a few but not of hundreds. step_dt becomes the length
// of the step taken; each step taken again counts in `retried`.
StepReport Simulation::take_step(double& step_dt, long& retried, double planned_end) {
  const double planned_dt = step_dt;
  // The inlets' schedules from the step's end, as a restart from its checkpoint takes them.
  auto set_inflow = [&] {
    const double t_end = step_dt == planned_dt ? planned_end : time_ + step_dt;
    flow_->set_inflow_time(inflow_time_after(config_.flow.boundaries, t_end, step_dt));
  };
  const auto& tc = config_.time;
  StepReport r;
  const bool may_retry = tc.adaptive;
  if (may_retry) {
    flow_->save_state();
    if (soil_) soil_->save_state();
  }
  auto take_again = [&](double shorter_dt) {  // from the state the step started from
    flow_->restore_state();
    if (soil_) soil_->restore_state();
    step_dt = shorter_dt;
    ++retried;
  };
  for (int attempt = 0;; ++attempt) {
    if (soil_) {  // explicit interface, then the implicit flow step
      soil_->advect(*flow_, step_dt);  // by the last step's faces, and its inlets' inflow
      set_inflow();
      soil_->refresh(*flow_);
      if (surface_tension_) surface_tension_->fill(soil_->soil_fraction(), *flow_);  // from the c just advected
      update_solve_region();
    } else {
      set_inflow();
    }
    try {
      r = flow_->step(step_dt);
    } catch (const LinearSolveFailure& e) {
      // A shorter step makes the systems better conditioned (the time term grows on the diagonal).
      if (!may_retry || attempt == max_step_retries) {
        if (soil_) write_history();
        throw DivergenceError(fmt::format("at t = {:.6g} s (step {}, dt = {:.3g} s): {}; {}", time_, steps_ + 1, step_dt,
                                          e.what(), last_output_kept));
      }
      take_again(0.1 * step_dt);
      continue;
    }
    if (!may_retry || attempt == max_step_retries) break;
    const double co = courant_after(step_dt);
    if (std::isfinite(co) && co <= retry_courant_factor * tc.courant) break;
    const double smaller = std::isfinite(co) ? step_dt * tc.courant / co : 0.1 * step_dt;
    take_again(std::clamp(smaller, 1e-3 * step_dt, 0.5 * step_dt));
  }
  if (soil_) soil_->transport_displacement(*flow_, step_dt);
  return r;
}

// Stops the run (DivergenceError) where the largest speed is not finite or beyond 1e6 m/s, saying
// where, with the history up to then.
void Simulation::stop_if_diverged(double speed, long steps) {
  if (std::isfinite(speed) && speed <= 1e6) return;
  if (soil_) write_history();  // the steps up to the failure, for finding where it began
  const auto f = flow_->fastest_cell();
  const long at_limit = flow_->solves_at_iteration_limit();
  throw DivergenceError(fmt::format("the solution diverged at t = {:.6g} s (step {}): largest speed {} m/s "
                                    "at x = {:.4g} m, y = {:.4g} m{}; {}{}",
                                    time_, steps, std::isnan(f.speed) ? "NaN" : fmt::format("{:.3g}", f.speed), f.x,
                                    f.y, grid_->dimension() == 3 ? fmt::format(", z = {:.4g} m", f.z) : std::string(),
                                    last_output_kept,
                                    at_limit > 0 ? fmt::format(" ({} linear solves had stopped at their "
                                                               "max_iterations)", at_limit)
                                                 : std::string()));
}

// max|dv/dt| / max|v| below time.steady_tolerance, from the velocities before the step (`before`,
// overwritten with the change).
bool Simulation::is_steady(OwnedVec (&before)[3], double step_dt, double speed) const {
  double change = 0.0;
  for (int a = 0; a < grid_->dimension(); ++a) {
    PetscCallAbort(grid_->comm(), VecAXPY(before[a], -1.0, flow_->velocity(a).global()));
    change = larger_or_nan(change, max_abs(grid_->comm(), before[a]));  // NaN is not steady
  }
  return change / step_dt < config_.time.steady_tolerance * std::max(speed, 1e-300);
}

RunSummary Simulation::run(const StepObserver& after_step) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_progress = start;
  RunSummary summary;
  const auto& tc = config_.time;
  // A restart goes on with the step the stopped run would have taken, within the case's present
  // bounds: a lower time.max_dt, or a fixed time.dt, applies from the first step (a new courant
  // number from the second, as the step is chosen from the flow).
  double dt = !restarted_ ? std::min(tc.dt, tc.max_dt)
                          : (tc.adaptive ? std::min(restart_dt_, tc.max_dt) : std::min(tc.dt, tc.max_dt));
  if (surface_tension_) dt = std::min(dt, capillary_time_step());  // a fixed step too
  if (!restarted_) write_output();
  OwnedVec previous[3];  // freed also when the loop ends in an exception (divergence, an observer that stops the run)
  const int components = grid_->dimension();
  for (int a = 0; a < components; ++a) PetscCallAbort(grid_->comm(), VecDuplicate(flow_->velocity(a).global(), previous[a].put()));
  // Whether the state at hand has been written, and checkpointed: at the start it has been written
  // (just above, or by the run a restart continues), and checkpointed if this is a restart.
  bool output_is_current = true;
  bool checkpoint_is_current = restarted_;
  while (time_ < tc.end * (1 - 1e-12) && steps_ < tc.max_steps) {
    const double t_out = next_output_time();
    // Steps land on output times, but for a run that seeks a steady state only on time.end: the
    // projection's discrete steady state depends a little on the step, so a step cut short for an
    // output, and its return to full length, disturb the velocity by more than the steady test
    // allows, and with a long relaxation. Such a run writes each output at the end of the step that
    // reaches its time.
    // Steps land on the times of the inlets' schedules too: a step of the schedule is met exactly.
    const double t_land =
        std::min(tc.steady_tolerance > 0.0 ? tc.end : t_out, next_inflow_time(config_.flow.boundaries, time_));
    double step_dt = dt;
    if (time_ + step_dt > t_land * (1 - 1e-12)) step_dt = t_land - time_;
    else if (time_ + 1.5 * step_dt > t_land) step_dt = 0.5 * (t_land - time_);  // avoid a sliver step
    for (int a = 0; a < components; ++a) PetscCallAbort(grid_->comm(), VecCopy(flow_->velocity(a).global(), previous[a]));
    double planned_end = time_ + step_dt;
    if (std::abs(planned_end - t_out) <= 1e-12 * std::max(1.0, t_out)) planned_end = t_out;  // as time_ below
    const StepReport r = take_step(step_dt, summary.retried_steps, planned_end);
    time_ += step_dt;
    if (soil_) record_history(step_dt);
    ++summary.steps;
    ++steps_;
    last_step_ = r;
    summary.outer_iterations += r.outer_iterations;
    if (!(r.velocity_change < config_.flow.numerics.outer_tolerance)) ++summary.steps_outer_unconverged;
    summary.momentum_iterations += r.momentum_iterations;
    summary.pressure_iterations += r.pressure_iterations;
    summary.pressure_solves += r.pressure_solves;

    const double speed = flow_->max_speed();
    stop_if_diverged(speed, steps_);  // numbered over the whole run, restarts included
    if (after_step) after_step(*this, step_dt);  // an accepted step: one that did not diverge
    // Neither stop holds while an inlet's schedule has a change to come, and the soil is not at rest
    // while an inlet lets soil in.
    const bool schedule_ahead = next_inflow_time(config_.flow.boundaries, time_) < tc.end;
    bool soil_coming_in = false;
    for (Side side : sides_of_dimension(grid_->dimension())) {
      const BoundaryCondition& bc = boundary(flow_->settings().boundaries, side);  // at the step's factor
      soil_coming_in |= carries_soil(bc) && bc.velocity[normal_axis(side)] != 0.0;
    }
    const bool steady = tc.steady_tolerance > 0.0 && !schedule_ahead && is_steady(previous, step_dt, speed);
    // The soil at rest (time.rest_speed): slower than it everywhere, once it has moved (the speed the
    // history recorded for this step).
    const bool at_rest = tc.rest_speed > 0.0 && soil_ && !schedule_ahead && !soil_coming_in &&
                         soil_speed_ < tc.rest_speed && soil_->largest_displacement() > soil_->moved_distance();
    const bool at_output = time_ >= t_out - 1e-12 * std::max(1.0, t_out);
    if (at_output && std::abs(time_ - t_out) <= 1e-12 * std::max(1.0, t_out)) time_ = t_out;
    // The steady state is written where it is reached, its line samples marked as such; so is the
    // soil at rest.
    steady_state_reached_ = steady;
    if (at_output || steady || at_rest) write_output();
    output_is_current = at_output || steady || at_rest;
    checkpoint_is_current = false;
    if (steady || at_rest) {
      summary.reached_steady_state = steady;
      summary.soil_at_rest = at_rest;
      break;
    }
    const auto now = clock::now();
    if (config_.output.progress_seconds > 0 &&
        std::chrono::duration<double>(now - last_progress).count() >= config_.output.progress_seconds) {
      last_progress = now;
      const double wall = std::chrono::duration<double>(now - start).count();
      const double rate = summary.steps / wall;
      const double eta = time_ > 0 ? wall * (tc.end - time_) / time_ : 0.0;
      if (rank_ == 0)
        fmt::print(stderr, "t = {:.5g} / {:.5g} s  dt = {:.3g} s  step {}  {:.1f} steps/s  {:.0f} s left\n", time_,
                   tc.end, step_dt, summary.steps, rate, eta);
    }
    // Sized from the step as planned, not as cut short to land on an output time or taken again
    // shorter: the Courant numbers set the next step, the short one does not hold back its growth.
    dt = choose_dt(dt);
    if (at_output) {
      write_checkpoint(dt);
      checkpoint_is_current = true;
    }
  }
  // A run that stops before time.end (steady, or out of steps) writes where it stopped, once, with a
  // checkpoint to go on from.
  if (summary.reached_steady_state || summary.soil_at_rest || steps_ >= tc.max_steps) {
    if (!output_is_current) write_output();  // out of steps
    if (!checkpoint_is_current) write_checkpoint(dt);
  }
  if (soil_) {
    const SoilBudget b = soil_->budget(*flow_);
    if (initial_soil_volume_ > 0.0) summary.soil_volume_error = b.soil_volume / initial_soil_volume_ - 1.0;
    // Relative to the larger of the initial soil and what entered (a domain that starts empty).
    const double scale = std::max(initial_soil_volume_, std::max(-b.soil_outflow, 0.0));
    if (scale > 0.0) summary.soil_balance_error = (b.soil_volume + b.soil_outflow - initial_soil_volume_) / scale;
  }
  summary.time = time_;
  summary.stopped_at_max_steps = !summary.reached_steady_state && !summary.soil_at_rest && steps_ >= tc.max_steps && time_ < tc.end * (1 - 1e-12);
  summary.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  summary.solves_at_iteration_limit = flow_->solves_at_iteration_limit();
  return summary;
}

}  // namespace granflow

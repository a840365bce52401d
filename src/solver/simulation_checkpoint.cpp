// Checkpoints: what a run writes to be continued exactly, and the restart that reads it back.
#include <fmt/format.h>

#include <algorithm>
#include <span>

#include "io/checkpoint.hpp"
#include "solver/simulation.hpp"

namespace granflow {

std::vector<Field*> Simulation::checkpoint_fields() {
  auto fields = flow_->checkpoint_fields();
  if (soil_)
    for (Field* f : soil_->checkpoint_fields()) fields.push_back(f);
  return fields;
}

std::string Simulation::checkpoint_field_names() {
  std::string names = flow_->checkpoint_field_names();
  if (soil_) names.append(" ").append(soil_->checkpoint_field_names());
  return names;
}

// The domain as a checkpoint records it, so that a restart cannot take the fields of another one.
std::string Simulation::domain() const {
  const auto& m = config_.mesh;
  if (m.dimension() == 3) {  // a mesh of layers: its depth and grading along z too
    std::string text = fmt::format("[{:.9g}, {:.9g}] x [{:.9g}, {:.9g}] x [{:.9g}, {:.9g}] (layers)", m.lower[0],
                                   m.upper[0], m.lower[1], m.upper[1], m.lower[2], m.upper[2]);
    if (m.grading[0] != 1.0 || m.grading[1] != 1.0 || m.grading[2] != 1.0)
      text += fmt::format(", grading [{:.9g}, {:.9g}, {:.9g}]", m.grading[0], m.grading[1], m.grading[2]);
    return text + obstacles_;
  }
  std::string text = fmt::format("[{:.9g}, {:.9g}] x [{:.9g}, {:.9g}] ({})", m.lower[0], m.upper[0], m.lower[1],
                                 m.upper[1], m.axisymmetric ? "axisymmetric" : "planar");
  // Graded cells lie elsewhere: a restart on other grading would read the fields into wrong cells.
  if (m.grading[0] != 1.0 || m.grading[1] != 1.0)
    text += fmt::format(", grading [{:.9g}, {:.9g}]", m.grading[0], m.grading[1]);
  return text + obstacles_;
}

namespace {

// A soil's rheology as the checkpoint's record of the physics gives it.
std::string rheology_record(const rheology::RheologyParameters& r) {
  if (r.friction == rheology::FrictionSource::mu_of_I)
    return fmt::format("{} with mu(I) friction, mu_s {:.9g}, mu_2 {:.9g}, I_0 {:.9g}, d {:.9g} m", rheology::to_string(r.model),
                       r.static_friction, r.limiting_friction, r.reference_inertial_number, r.grain_diameter);
  return fmt::format("{} with {} friction, phi {:.9g} deg, cohesion {:.9g} Pa", rheology::to_string(r.model),
                     rheology::to_string(r.friction), r.friction_angle_deg, r.cohesion);
}

// ... with, for a material of its own Matsuoka-Nakai surface, the fit of its k_MN.
std::string material_record(const rheology::RheologyParameters& r) {
  std::string text = rheology_record(r);
  if (r.model == rheology::Model::matsuoka_nakai)
    text += fmt::format(", {} fit", rheology::to_string(r.matsuoka_nakai_fit));
  return text;
}

}  // namespace

// The materials and gravity, as a checkpoint records them: a restart with others is most likely
// the wrong case file, though a deliberate change is allowed.
std::string Simulation::physics() const {
  const auto& g = config_.flow.gravity;
  std::string text = config_.mesh.dimension() == 3 ? fmt::format("gravity [{:.9g}, {:.9g}, {:.9g}]", g[0], g[1], g[2])
                                                   : fmt::format("gravity [{:.9g}, {:.9g}]", g[0], g[1]);
  if (!config_.soil) return text + fmt::format("; fluid {:.9g} kg/m^3, {:.9g} Pa s", config_.fluid.density, config_.fluid.viscosity);
  const SoilSettings& s = *config_.soil;
  text += fmt::format("; air {:.9g} kg/m^3, {:.9g} Pa s; soil {:.9g} kg/m^3", s.air_density, s.air_viscosity, s.soil_density);
  // Recorded only where there is one, so that a record without it stands for none.
  std::string tension = s.surface_tension > 0.0 ? fmt::format("; surface tension {:.9g} N/m", s.surface_tension) : "";
  if (s.surface_tension > 0.0 && s.contact_angle != 90.0)
    tension += fmt::format(", contact angle {:.9g} deg", s.contact_angle);
  if (!s.rheology) return text + fmt::format(", {:.9g} Pa s", s.soil_viscosity) + tension;
  const auto& r = *s.rheology;
  text += ", " + rheology_record(r);
  for (const auto& m : s.materials) {
    const auto& q = m.rheology;
    if (q.model == r.model && q.friction == rheology::FrictionSource::constant &&
        q.matsuoka_nakai_fit == r.matsuoka_nakai_fit)  // as records before materials had more
      text += fmt::format("; {}: phi {:.9g} deg, cohesion {:.9g} Pa", m.name, q.friction_angle_deg, q.cohesion);
    else
      text += fmt::format("; {}: {}", m.name, material_record(q));
    if (q.density != s.soil_density) text += fmt::format(", {:.9g} kg/m^3", q.density);
  }
  return text + tension;
}

// The sides' conditions, as a checkpoint records them (apart from the physics, so that a checkpoint
// written before they were recorded is not taken for one of other physics).
std::string Simulation::boundaries() const {
  std::string text;
  const bool layers = config_.mesh.dimension() == 3;
  for (Side side : sides_of_dimension(config_.mesh.dimension())) {
    const BoundaryCondition& bc = boundary(config_.flow.boundaries, side);
    text += fmt::format("{}{} ", text.empty() ? "" : "; ", side_name(side));
    switch (bc.kind) {
      case BoundaryKind::wall:
        text += layers ? fmt::format("wall [{:.9g}, {:.9g}, {:.9g}] m/s", bc.velocity[0], bc.velocity[1],
                                     bc.velocity[2])
                       : fmt::format("wall [{:.9g}, {:.9g}] m/s", bc.velocity[0], bc.velocity[1]);
        if (bc.friction)  // a wall without friction reads as before its friction could be given
          text += fmt::format(", friction {:.9g}, adhesion {:.9g} Pa", bc.friction->friction_coefficient,
                              bc.friction->adhesion);
        break;
      case BoundaryKind::slip: text += "slip"; break;
      case BoundaryKind::periodic: text += "periodic"; break;
      case BoundaryKind::atmosphere:
        text += fmt::format("atmosphere {:.9g} Pa {}, inflow c {:.9g}", bc.pressure,
                            bc.total_pressure ? "total" : "static", bc.inflow_soil_fraction);
        break;
      case BoundaryKind::inlet:
        text += layers ? fmt::format("inlet [{:.9g}, {:.9g}, {:.9g}] m/s", bc.velocity[0], bc.velocity[1],
                                     bc.velocity[2])
                       : fmt::format("inlet [{:.9g}, {:.9g}] m/s", bc.velocity[0], bc.velocity[1]);
        text += fmt::format(", c {:.9g} below {:.9g} m, material {}", bc.inflow_soil_fraction, bc.inflow_soil_depth,
                            bc.inflow_material);
        for (size_t k = 0; k < bc.inflow_schedule.size(); ++k)
          text += fmt::format("{}[{:.9g} s, {:.9g}]", k == 0 ? ", schedule " : " ", bc.inflow_schedule[k][0],
                              bc.inflow_schedule[k][1]);
        for (int axis = 0; axis < 3; ++axis)  // an inlet open over its whole side reads as before spans
          if (std::isfinite(bc.inflow_span[axis][0]) || std::isfinite(bc.inflow_span[axis][1]))
            text += fmt::format(", span_{} [{:.9g}, {:.9g}] m", "xyz"[axis], bc.inflow_span[axis][0],
                                bc.inflow_span[axis][1]);
        break;
    }
  }
  for (size_t k = 0; k < config_.obstacle_friction.size(); ++k)  // none without an obstacle's own friction
    if (const auto& f = config_.obstacle_friction[k])
      text += fmt::format("; obstacle[{}] friction {:.9g}, adhesion {:.9g} Pa", k, f->friction_coefficient, f->adhesion);
  return text;
}

void Simulation::write_checkpoint(double next_dt) {
  if (out_.empty() || !config_.output.checkpoints) return;
  RunCheckpoint run{time_, next_dt, output_index_, dissipated_energy_, initial_soil_volume_, history_, {}, domain(), steps_, physics(),
                    checkpoint_field_names(), boundaries(), boundary_work_};
  if (series_) run.series = series_->entries();
  CheckpointScalars scalars{{flow_->last_dt()}, {}};
  if (soil_) {
    const CheckpointScalars own = soil_->checkpoint_scalars();
    scalars.shared.insert(scalars.shared.end(), own.shared.begin(), own.shared.end());
    scalars.summed = own.summed;
  }
  const auto fields = checkpoint_fields();
  granflow::write_checkpoint(grid_->comm(), out_, {grid_->nx(), grid_->ny(), grid_->nz()}, run, fields, scalars);
  // A run restarted from here builds its preconditioners afresh; so does this one, to go on alike.
  flow_->rebuild_preconditioners();
}

void Simulation::restart() {
  if (out_.empty()) throw CheckpointError("a restart needs the output directory of the earlier run");
  const auto fields = checkpoint_fields();
  CheckpointScalars scalars;
  RunCheckpoint run = read_checkpoint(grid_->comm(), out_, {grid_->nx(), grid_->ny(), grid_->nz()}, domain(), checkpoint_field_names(),
                                      fields, scalars);
  flow_->clear_blocked_cells();  // the fields were read with their ghosts, the blocked cells' mirrors among them
  if (soil_) {
    soil_->clear_blocked_cells();
    soil_->check_restored_fraction();
  }
  if (!(config_.time.end > run.time * (1 + 1e-12)))
    throw CheckpointError(fmt::format("time.end = {} s is not past the checkpoint's t = {:.9g} s: raise it to run on",
                                      config_.time.end, run.time));
  if (run.steps >= config_.time.max_steps)
    throw CheckpointError(fmt::format("time.max_steps = {} is not past the checkpoint's {} steps (it counts the "
                                      "whole run's): raise it to run on",
                                      config_.time.max_steps, run.steps));
  // The flow's one number, the last step's size, comes first; the soil checks its own numbers (and
  // takes those of checkpoints written before the periodic join's moment was kept).
  if (scalars.shared.empty() || (!soil_ && (scalars.shared.size() != 1 || !scalars.summed.empty())))
    throw CheckpointError("the checkpoint's state does not match this case's model");
  if (soil_) soil_->restore_scalars(std::span<const double>(scalars.shared).subspan(1), scalars.summed);
  flow_->set_last_dt(scalars.shared[0]);
  // The inlets' faces as the last step left them (of the case's inlets, which may have changed).
  flow_->set_inflow_time(inflow_time_after(config_.flow.boundaries, run.time, scalars.shared[0]));
  flow_->impose_inlet_face_velocities();
  time_ = run.time;
  restart_time_ = run.time;
  restart_dt_ = run.next_dt;
  steps_ = run.steps;
  if (const std::string ours = physics(); rank_ == 0 && !run.physics.empty() && run.physics != ours)
    fmt::print(stderr, "warning: the case's physics ({}) differs from the checkpoint's run ({}); continuing with the case's\n",
               ours, run.physics);
  if (const std::string ours = boundaries(); rank_ == 0 && !run.boundaries.empty() && run.boundaries != ours)
    fmt::print(stderr, "warning: the case's boundaries ({}) differ from the checkpoint's run ({}); continuing with the "
                       "case's\n", ours, run.boundaries);
  output_index_ = run.output_index;
  dissipated_energy_ = run.dissipated_energy;
  boundary_work_ = run.boundary_work;
  initial_soil_volume_ = run.initial_soil_volume;
  history_ = std::move(run.history);
  // A checkpoint's history written before the soil_speed column (the 13th) or the boundary_work
  // column (the 14th) has a field or two fewer: those columns are left empty there (NaN), so that each
  // row stays under its header. (Its boundary_work goes on from 0.)
  constexpr std::size_t base_fields = 14;
  const bool layers = grid_->dimension() == 3;
  const std::size_t expected = base_fields + (layers ? 18 : 8) + (blocked_ ? (layers ? 3 : 2) : 0);
  for (auto& row : history_) {
    const std::size_t fields = 1 + std::count(row.begin(), row.end(), ',');
    if (fields + 2 != expected && fields + 1 != expected) continue;
    const bool without_speed = fields + 2 == expected;
    std::size_t at = 0;
    for (std::size_t k = 0; k < (without_speed ? 12 : 13); ++k) at = row.find(',', at) + 1;
    row.insert(at, without_speed ? "nan,nan," : "nan,");
  }
  if (series_) series_->restore_entries(std::move(run.series));
  if (soil_) soil_->refresh(*flow_);
  flow_->update_properties();  // density and viscosity of the restored state, for observers and output
  restarted_ = true;
}

}  // namespace granflow

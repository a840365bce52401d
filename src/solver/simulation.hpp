#pragma once
// The time loop of a case: adaptive steps, output at requested times, progress, divergence guard.
#include <filesystem>
#include <functional>
#include <memory>

#include "io/case_file.hpp"
#include "io/vtk_series.hpp"
#include "mesh/grid.hpp"
#include "solver/divergence_error.hpp"
#include "solver/flow_solver.hpp"
#include "solver/soil_phase.hpp"
#include "solver/surface_tension_force.hpp"

namespace granflow {

struct RunSummary {
  double soil_volume_error = 0.0;  // relative change of the soil volume over the run
  // Relative change of the soil in the domain plus what left it through open sides: round-off, unless
  // the solves were inexact (their divergence makes and destroys soil).
  double soil_balance_error = 0.0;
  long steps = 0;
  long retried_steps = 0;  // steps taken again with a smaller time step
  double time = 0.0;
  double wall_seconds = 0.0;
  long outer_iterations = 0;
  // Steps whose outer iterations ran out before the velocity changed by less than
  // numerics.outer_tolerance (most steps, with the few iterations of the collapse cases).
  long steps_outer_unconverged = 0;
  long momentum_iterations = 0;
  long pressure_iterations = 0;
  long pressure_solves = 0;
  long solves_at_iteration_limit = 0;  // linear solves that stopped at max_iterations before rtol
  bool reached_steady_state = false;
  bool soil_at_rest = false;          // stopped at time.rest_speed
  bool stopped_at_max_steps = false;  // before time.end
};


// What a run's start finds that the case file alone cannot: a mesh that cannot be laid out on the
// ranks of comm (GridError), initial shapes that miss every cell's samples (CaseError). Collective;
// it lays out the grid only, not the solver (granflow check). Returns what it laid out, for the user
// to compare with what was meant.
struct InitialState {
  long blocked_cells = 0;    // by the obstacles
  std::string ridges_lowered;  // the obstacles' ridges one cell wide lowered to the mesh ("" if none)
  double soil_volume = 0.0;  // in open cells: m^2 per metre of depth, or m^3 per radian if axisymmetric
  double soil_in_obstacles = 0.0;  // what the initial shapes hold in blocked cells, left out (same units)
  std::vector<double> material_volumes;  // with [[soil.materials]]: the rheology's own soil's, then each material's
};
InitialState check_initial_state(MPI_Comm comm, const CaseConfig& config);

class Simulation {
 public:
  // output_dir empty: no files are written (tests).
  Simulation(MPI_Comm comm, const CaseConfig& config, std::filesystem::path output_dir);
  ~Simulation();

  // Called after every accepted step, with the step's size (diagnostics and tests; not in a hot loop).
  using StepObserver = std::function<void(Simulation&, double dt)>;
  RunSummary run(const StepObserver& after_step = {});
  const Grid& grid() const { return *grid_; }
  // The obstacles' ridges one cell wide that laying out lowered to the mesh, for the user ("" if none).
  const std::string& ridges_lowered() const { return ridges_lowered_; }
  FlowSolver& flow() { return *flow_; }
  SoilPhase* soil() { return soil_.get(); }
  const CaseConfig& config() const { return config_; }
  double time() const { return time_; }
  const StepReport& last_step() const { return last_step_; }  // the flow step last taken
  double dissipated_energy() const { return dissipated_energy_; }  // J per metre depth (or radian), so far
  // The energy brought in through the sides so far, J per metre depth (or radian): the kinetic and
  // potential energy carried in less that carried out, and the work of the sides' forces.
  double boundary_work() const { return boundary_work_; }

  // Writes the field series entry and the line samples for the current state.
  void write_output();

  // Continues from the checkpoint in the output directory (written at the last output time of an
  // earlier run of this case), so that run() carries on exactly as the earlier run would have.
  // On another number of ranks it carries on to the solver's round-off. Throws CheckpointError if there
  // is none or it does not fit this case.
  void restart();

 private:
  double next_output_time() const;
  void record_history(double dt);
  void update_solve_region();
  void write_history() const;
  void write_column_heights_3d(const std::vector<double>& c, const std::string& stamp) const;
  void write_soil_lines() const;
  void write_lode_energy() const;
  void write_line_samples(const std::vector<double>& u, const std::vector<double>& v,
                          const std::vector<double>& p) const;
  double choose_dt(double dt_previous) const;
  // planned_end: where the step as planned ends (snapped to an output time as the run's time will be);
  // its inlets' schedules are taken from there.
  StepReport take_step(double& step_dt, long& retried, double planned_end);
  void stop_if_diverged(double speed, long steps);
  bool is_steady(OwnedVec (&before)[3], double step_dt, double speed) const;
  double courant_after(double dt) const;  // flow Courant number of the current velocities over dt
  std::vector<Field*> checkpoint_fields();
  std::string checkpoint_field_names();
  void write_checkpoint(double next_dt);
  std::string domain() const;
  std::string physics() const;
  std::string boundaries() const;

  static constexpr int max_step_retries = 4;
  static constexpr double retry_courant_factor = 4.0;  // retry a step above this multiple of the target

  CaseConfig config_;
  std::filesystem::path out_;
  std::unique_ptr<Grid> grid_;
  std::unique_ptr<Field> blocked_;  // the obstacles' cells (mesh/obstacles.hpp); null without obstacles
  std::unique_ptr<Field> obstacle_index_;  // each blocked cell's obstacle, with obstacles of their own friction
  int wall_column_ = 0;             // the first column with an open cell: the history's wall height (rank 0)
  std::string obstacles_;           // the blocked cells as domain() records them ("" without obstacles)
  std::string ridges_lowered_;      // the obstacles' ridges one cell wide lowered to the mesh ("" if none)
  std::vector<double> blocked_on_root_;  // the mask gathered to rank 0 (empty elsewhere, and without obstacles)
  std::function<bool(int, int)> open_square(int layer) const;
  bool in_blocked_cell(double x, double y, double z) const;
  std::unique_ptr<FlowSolver> flow_;
  std::unique_ptr<SoilPhase> soil_;
  std::unique_ptr<SurfaceTensionForce> surface_tension_;  // soil.surface_tension > 0
  // Its limit on the step (solver/surface_tension_force.hpp), shortest for the lightest soil.
  double capillary_time_step() const {
    double lightest = config_.soil->soil_density;
    for (const auto& m : config_.soil->materials) lightest = std::min(lightest, m.rheology.density);
    return surface_tension_->time_step_limit(lightest, config_.soil->air_density);
  }
  std::unique_ptr<VtkSeries> series_;
  std::vector<std::string> history_;  // rows of history.csv, rewritten whole at each output
  double dissipated_energy_ = 0.0;
  double boundary_work_ = 0.0;
  double soil_speed_ = 0.0;  // largest speed over the soil (c >= 0.5) at the end of the last step, as recorded
  double initial_soil_volume_ = 0.0;
  double time_ = 0.0;
  double restart_dt_ = 0.0;  // the step to continue with after restart()
  bool restarted_ = false;
  bool steady_state_reached_ = false;  // the outputs written now are the run's steady state
  double restart_time_ = 0.0;  // the checkpoint's time, after restart()
  StepReport last_step_;
  long steps_ = 0;  // steps of the whole run, over restarts (time.max_steps counts these)
  int output_index_ = 0;
  bool run_recorded_ = false;  // the record of the run's line samples is written (io/run_directory.hpp)
  int rank_ = 0;
};

}  // namespace granflow

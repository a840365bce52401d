#pragma once
// Pressure-based solver for the incompressible Navier-Stokes equations of a mixture with cell-wise
// density and viscosity ([VoF] Eqs. 17-18, App. B; [YS] Eqs. 2-3), on collocated cells:
//   - backward Euler in time, implicit upwind convection with deferred correction to the chosen
//     scheme, the viscous stress div(mu (grad v + grad v^T)) split as 2 mu grad(v_c) implicit on
//     every face and the remainder lagged (momentum_equation.cpp);
//   - outer iterations with the properties updated in each, as in [VoF] Alg. 1 (flow_solver.cpp);
//     in each, velocity and pressure either in one coupled solve with Rhie-Chow face fluxes
//     (coupled_step.cpp), or segregated: a momentum predictor and a projection or PISO pressure
//     corrections (segregated_pressure.cpp);
//   - gravity enters as a face force rho_f g next to the pressure gradient, and cell forces are
//     reconstructed from face forces, so a fluid at rest under gravity stays at rest exactly.
#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "mesh/field.hpp"
#include "mesh/field_snapshot.hpp"
#include "mesh/grid.hpp"
#include "mesh/petsc_handle.hpp"
#include "solver/cell_faces.hpp"
#include "solver/flow_settings.hpp"
#include "solver/linear_solver.hpp"
#include "solver/solve_region.hpp"

namespace granflow {

struct StepReport {
  int outer_iterations = 0;
  int momentum_iterations = 0;  // summed over components and outer iterations
  int pressure_iterations = 0;  // summed over all pressure solves
  int pressure_solves = 0;
  double velocity_change = 0.0;  // relative change in the last outer iteration
};

class FlowSolver {
 public:
  // Called in each outer iteration, before momentum assembly (twice in the first under the look-ahead
  // viscosity, update_properties_ahead): fill density() and viscosity() for the owned cells (ghosts are
  // refreshed by the solver afterwards).
  using PropertyUpdate = std::function<void(FlowSolver&)>;

  FlowSolver(const Grid& grid, const FlowSettings& settings);
  ~FlowSolver();

  const Grid& grid() const { return grid_; }
  const FlowSettings& settings() const { return settings_; }
  Field& velocity(int axis) { return *vel_[axis]; }
  const Field& velocity(int axis) const { return *vel_[axis]; }
  Field& pressure() { return *p_; }
  const Field& pressure() const { return *p_; }
  Field& density() { return *rho_; }
  const Field& density() const { return *rho_; }
  Field& viscosity() { return *mu_; }
  const Field& viscosity() const { return *mu_; }
  // Viscosity on the faces, read and written in the local (ghosted) array: [j][i] of axis 0 is the
  // face between cells (i, j) and (i+1, j), [j][-1] and [j][nx-1] the west and east boundary faces;
  // axis 1 likewise in j. Holds the faces of the owned cells.
  Field& face_viscosity(int axis) { return *face_mu_[axis]; }
  const Field& face_viscosity(int axis) const { return *face_mu_[axis]; }
  // Normal velocity at the east (axis 0) or north (axis 1) face of each cell; the west/south faces
  // of the owned block (global index -1 at the domain boundary) are held in the ghost entries.
  Field& face_velocity(int axis) { return *face_[axis]; }
  // External body force per unit volume (N/m^3) besides gravity, e.g. a manufactured-solution source.
  // Zero unless enable_body_force() was called.
  void enable_body_force();
  Field& body_force(int axis) { return *body_force_[axis]; }
  // A force per unit volume on the interior faces (N/m^3, indexed like face_velocity), acting where
  // rho_f g does and balanced by the pressure gradient the same way: the surface tension
  // sigma kappa_f grad_f(c) of models/interface/surface_tension.hpp. Zero unless enabled; its owner
  // fills it before each step (boundary faces are not read).
  void enable_face_source();
  Field& face_source(int axis) { return *face_source_[axis]; }
  bool has_face_source() const { return face_source_[0] != nullptr; }
  const Field& face_velocity(int axis) const { return *face_[axis]; }

  // The mass the momentum equation carries under numerics.momentum_transport = "conservative" (coupled
  // solve only): the mixture density at the start of the step (owned cells) and each face's mass flux
  // over the step (kg m^-2 s^-1, indexed like face_velocity), both from the soil fraction's own
  // advection (SoilPhase::advect), so that momentum moves with the mass the VoF moves. Both are held
  // in the local arrays only (their global vectors are not kept current). Until enabled the momentum
  // equation takes the cell's density times the face velocity.
  void enable_mass_transport();
  bool carries_mass_transport() const { return start_density_ != nullptr; }
  Field& start_density() { return *start_density_; }
  // After the soil's advection has filled start_density and the mass fluxes: the momentum each cell
  // starts the step with, from the mass its momentum was carried with over the last step, and the mass
  // this step's fluxes leave in it (models/mixture/carried_momentum.hpp).
  void carry_momentum_mass(double dt);
  Field& mass_flux(int axis) { return *mass_flux_[axis]; }

  // Obstacles and terrain (mesh/obstacles.hpp): the mask of blocked cells, with ghosts, kept by the
  // caller; set once, before the initial state. Their faces to open cells are no-slip walls.
  void set_blocked(const Field* mask);
  const Field* blocked() const { return blocked_; }

  void set_property_update(PropertyUpdate f) { property_update_ = std::move(f); }
  // Fills face_viscosity() after the cell properties and their ghosts; without it the faces take
  // the mean of their cells' viscosities (numerics.face_viscosity).
  void set_face_viscosity_update(PropertyUpdate f) { face_viscosity_update_ = std::move(f); }
  // Applies the property update and refreshes ghosts of density and viscosity.
  void update_properties();
  // Pressure in hydrostatic balance with the current density: integrated down each column from the
  // top with the trapezoidal rule between cell centres, which is exactly what the face forces
  // balance. Requires a closed or atmosphere top; uses the top boundary's pressure as reference.
  void set_hydrostatic_pressure();
  void refresh_ghosts();

  StepReport step(double dt);
  // Snapshot of the state a step starts from (velocities, face velocities and forces, pressure, and
  // the mass each cell's momentum was carried with), so that a step that went wrong can be taken again
  // with a smaller time step.
  void save_state();
  void restore_state();
  // Zero velocity in the blocked cells' global values, after they were read from local ones.
  void clear_blocked_cells();
  // Inlets: the velocity of those of a schedule at time t (Simulation takes the middle of the step after
  // the one about to be solved: the faces it leaves carry that inflow over that step's sweeps);
  // whether any has one.
  bool set_inflow_time(double t);
  // Inlets' faces at their velocity (at the start, and after a checkpoint, whose inlet the case may
  // have changed).
  void impose_inlet_face_velocities();
  // What a checkpoint holds to continue a run exactly: the fields a step starts from, and the last
  // step's size (the look-ahead extrapolates with it).
  std::vector<Field*> checkpoint_fields() { return state_fields(); }
  // The names of checkpoint_fields(), in their order, blank-separated.
  std::string checkpoint_field_names();
  double last_dt() const { return dt_; }
  void set_last_dt(double dt) { dt_ = dt; }
  // Every linear solver builds its preconditioner anew at its next solve, as after a restart.
  void rebuild_preconditioners();

  // numerics.air_band > 0: the coupled solve covers only the cells of its region (SolveRegion); the
  // air beyond is held at rest at its hydrostatic pressure. Without an air band both are no-ops.
  bool solve_region_covers(const Field& cells) const;
  bool solve_region_laid() const;  // false also without an air band
  void set_solve_region(const Field& cells);
  // Linear solves so far that stopped at their max_iterations before their rtol (LinearSolver).
  long solves_at_iteration_limit() const;
  // Cells the last coupled solve covered, over all ranks (all of them without an air band).
  long solve_region_cells() const { return solve_region_ ? solve_region_->cell_count() : grid_.cell_count(); }

  // Largest |u| dt / h over cells, for the Courant condition; with a region (a ghosted fraction
  // field), only over cells whose 3 x 3 neighbourhood holds some of it.
  double max_courant(double dt, const Field* region = nullptr) const;
  double max_speed() const;
  // The cell with the largest speed (a NaN counts as largest), on every rank.
  struct FastestCell {
    double speed = 0.0, x = 0.0, y = 0.0, z = 0.0;
  };
  FastestCell fastest_cell() const;
  // Largest |div v| * V over owned cells, from the face velocities (volumetric imbalance, m^2/s in 2D).
  double max_divergence() const;
  // Force of the flow on each side of the domain, (x, y, z) indexed by Side, summed over ranks (N per
  // metre of depth on a planar mesh, per radian in axisymmetric cases, N on a mesh of layers; z and
  // the front and back 0 on one layer): the pressure and viscous traction on a wall or slip side, the
  // boundary pressure on an atmosphere side (side_force.cpp). Collective.
  std::array<std::array<double, 3>, 6> side_forces() const;
  // Force of the flow on the obstacles, all together (N/m), as on a static no-slip wall. Collective.
  std::array<double, 3> obstacle_force() const;
  // Both at once, in one pass over the faces and one reduction (the history's, every step).
  // And the work the sides' forces do on the flow per unit time, W per metre of depth (W on a mesh of
  // layers): a moving wall's and an inlet's, and an atmosphere's pressure on what crosses it.
  struct WallForces {
    std::array<std::array<double, 3>, 6> sides;
    std::array<double, 3> obstacle;
    double power = 0.0;
  };
  WallForces wall_forces() const;

 private:
  void fill_velocity_ghosts();
  std::vector<Field*> state_fields();  // what a step starts from: velocities, face velocities and forces, p
  std::vector<std::pair<const char*, Field*>> named_state_fields();
  void update_boundary_heads();
  // Hydrostatic head below the top at the atmosphere face of side s of cell (i, j, k) (y_face: the
  // face's height).
  double boundary_head(Side s, int i, int j, int k, double rho, double y_face) const;
  // The pressure the atmosphere of side s imposes on the boundary face of cell (i, j, k), from the state
  // in the given local arrays (density, cell velocities, face velocities): p0 plus the head below
  // the top, less rho v_n^2 / 2 (the cell's velocity normal to the side) where it flows in at total
  // pressure.
  double atmosphere_face_pressure(Side s, int i, int j, int k, VolumeView rho, const VolumeView velocity[],
                                  const VolumeView face_velocity[]) const;
  void fill_scalar_ghosts(Field& f);
  // The fields of one quantity per axis as fill_owned_faces_any takes them (null beyond the dimension).
  static std::array<Field*, 3> per_axis(std::unique_ptr<Field> (&fields)[3]) {
    return {fields[0].get(), fields[1].get(), fields[2].get()};
  }
  void face_viscosity_from_cells();
  void compute_face_forces();
  void extrapolate_velocity(double ratio);
  void update_properties_ahead();
  void update_properties_at_mean_pressure();
  // Momentum equation (momentum_equation.cpp).
  void assemble_momentum(double dt);
  int solve_momentum();
  void compute_velocity_without_pressure();
  // Coupled velocity-pressure solve (coupled_step.cpp).
  void create_coupled_system();
  void store_cell_forces();
  // by_first_factorisation: numerics.later_iterations = "first_factorisation" in a later outer iteration.
  int solve_coupled(bool by_first_factorisation);  // one outer iteration of the coupled solve, from the pieces below
  void compute_mobilities();
  class CoupledRows;  // the rows of one cell (coupled_step.cpp)
  void fill_coupled_rows();
  int solve_coupled_rows(bool by_first_factorisation);
  void update_coupled_face_velocities();
  double coupled_mobility(VolumeView rau, int i, int j, int k, int in, int jn, int kn) const;
  size_t boundary_face_index(Side s, int i, int j, int k) const;  // into solved_boundary_pressure_[s]
  double pressure_at_rest(double rho, int j) const;  // air outside the solve region
  // The ambient's weight per unit volume along `axis` that its mean pressure gradient carries along a
  // periodic x (FlowSettings::periodic_ambient_density), taken off every face's weight rho_f g; 0 otherwise.
  double ambient_weight(int axis) const { return axis == 0 ? settings_.periodic_ambient_density * settings_.gravity[0] : 0.0; }
  // The balanced force per volume on cell (i, j, k) along `axis` from the face forces ff of that axis.
  double cell_force(int axis, int i, int j, int k, VolumeView ff, VolumeView rho) const;
  double cell_force(int axis, int i, int j, const double* const* ff, const double* const* rho) const {
    return cell_force(axis, i, j, 0, PlaneAsVolume(ff), PlaneAsVolume(rho));
  }
  // Segregated pressure step (segregated_pressure.cpp).
  double face_coefficient(VolumeView rau, VolumeView rho, int i, int j, int k, const FaceGeometry& fg) const;
  void assemble_pressure_matrix();
  int solve_pressure();  // one pressure step, from the pieces below
  void assemble_pressure_rhs();
  void correct_velocities();
  void hold_pressure_at_top();  // closed domains: the pressure level

  const Grid& grid_;
  FlowSettings settings_;
  PropertyUpdate property_update_;
  PropertyUpdate face_viscosity_update_;

  // Per axis of the mesh: [2] only on a mesh of layers.
  std::unique_ptr<Field> vel_[3], vel_old_[3], face_[3], face_old_[3], face_force_[3];
  std::unique_ptr<Field> outer_start_[3];  // the velocity an outer iteration starts from, for its change
  // first_viscosity = look_ahead: the extrapolated velocity, and the viscosities at u^n it is weighed against
  std::unique_ptr<Field> vel_ahead_[3], mu_now_, face_mu_now_[3];
  // viscosity_pressure = mean_of_last_two: the pressure the last iteration started from, and the mean
  std::unique_ptr<Field> p_last_iterate_, p_mean_;
  std::unique_ptr<Field> p_, rho_, mu_, face_mu_[3];
  std::unique_ptr<Field> body_force_[3];
  std::unique_ptr<Field> face_source_[3];  // enable_face_source
  // The face source on face fg of cell (i, j, k) (0 without one), from the local arrays of face_source_.
  static double face_source_on(const VolumeView source[], int i, int j, int k, const FaceGeometry& fg) {
    return source[fg.axis] ? on_face(source, i, j, k, fg) : 0.0;
  }
  // The mass per volume each cell's momentum was carried with over the last step (state: it spans two
  // steps), and the density of the momentum the step starts with (carry_momentum_mass).
  std::unique_ptr<Field> carried_density_, start_momentum_density_;
  std::unique_ptr<Field> start_density_, mass_flux_[3];  // enable_mass_transport, mass flux per axis of the mesh
  FieldSnapshot saved_;  // save_state()
  // The velocity per unit of force density a cell's momentum row gives (OpenFOAM's rAU): V / a_P under
  // PISO and the coupled solve ([VoF] Eq. 28's A_i d_i / A_P, a cell's V / a_P), dt / rho under the projection.
  std::unique_ptr<Field> pressure_mobility_[3];
  // Segregated steps only: the velocity without the pressure force (OpenFOAM's HbyA), and the share of
  // the old time level in a_P, rho V / (dt a_P).
  std::unique_ptr<Field> velocity_without_pressure_[3], old_time_share_[3];

  // Momentum coefficients of the owned cells (row-major over the owned box). Off-diagonal
  // coefficients are stored positive (matrix entry = -a_nb) and shared by both components, one array
  // per face in the order of cell_faces.hpp: east, west, north, south, back, front.
  std::vector<double> a_neighbour_[6];
  std::vector<double> a_centre_[3], source_[3];

  // The segregated steps' systems (none under the coupled solve).
  OwnedMat momentum_matrix_[3];
  OwnedMat pressure_matrix_;
  OwnedNullSpace pressure_null_space_;
  OwnedVec rhs_;
  std::unique_ptr<LinearSolver> momentum_solver_[3];
  std::unique_ptr<LinearSolver> pressure_solver_;
  OwnedDm coupled_dm_;  // (u, v, p) per cell, (u, v, w, p) on a mesh of layers; the grid's layout
  OwnedMat coupled_matrix_;
  OwnedVec coupled_rhs_, coupled_solution_;
  std::unique_ptr<LinearSolver> coupled_solver_;  // numerics.air_band = 0
  std::unique_ptr<SolveRegion> solve_region_;      // numerics.air_band > 0
  std::unique_ptr<Field> cell_force_[3];  // lagged balanced cell force of the Rhie-Chow flux, per axis
  // The atmosphere's pressure on each boundary face as the last coupled system took it, per side, at
  // boundary_face_index (NaN where the system held no row).
  std::array<std::vector<double>, 6> solved_boundary_pressure_;  // indexed by Side
  // The open upright sides' hydrostatic heads, indexed by Side (south and north unused): [n * ny + j]
  // for column n along the side (its layer k on west and east, its x index on front and back).
  std::vector<double> side_head_[6];
  bool has_pressure_boundary_ = false;
  bool pins_pressure_level_ = false;  // the last coupled system held the level in a row (closed domain)
  const Field* blocked_ = nullptr;  // set_blocked
  int pin_i_ = 0, pin_j_ = 0, pin_k_ = 0;  // the cell whose continuity row holds a closed domain's level
  long open_cells_ = 0;            // cells not blocked, over all ranks
  bool shared_momentum_matrix_ = true;  // no slip walls: the components share their matrix
  int dimension_ = 2;                   // the mesh's: how many velocity components there are
  double dt_ = 0.0;        // the last step's size
  double saved_dt_ = 0.0;  // save_state()
};

}  // namespace granflow

#pragma once
// The soil phase on the grid: its fraction c, carried by geometric VoF advection; the mixture
// properties and the granular viscosity it gives the flow solver; the Eulerian displacement and
// the Euler-Almansi strain ([VoF] Eqs. 13-16, 19-20). Its state, checkpoint and ghosts are in
// soil_phase.cpp, the properties it gives the flow in soil_properties.cpp, its transport in
// soil_advection.cpp, and the strain and the history's measures in soil_diagnostics.cpp.
#include <algorithm>
#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "mesh/column_depth.hpp"
#include "mesh/field.hpp"
#include "mesh/field_snapshot.hpp"
#include "models/interface/vof_advection.hpp"
#include "models/rheology/granular_rheology.hpp"
#include "models/rheology/lode_histogram.hpp"
#include "solver/flow_solver.hpp"
#include "solver/soil_settings.hpp"

namespace granflow {

struct SoilBudget {
  double soil_volume = 0, air_volume = 0;
  double kinetic_energy = 0, potential_energy = 0;  // J per metre depth, with the phases' masses
  double dissipation_rate = 0;                      // W per metre depth, int 2 mu D:D dV
  double mixture_mass = 0;                          // kg per metre depth, int rho dV of the mixture
  double soil_outflow = 0;                          // soil volume carried out through open sides so far
  // W per metre depth: the kinetic and potential energy the flow carries in through the sides per
  // unit time (out: negative), with the phases' masses, as the energies above take them
  double convected_energy_rate = 0;
};

class SoilPhase {
 public:
  SoilPhase(const Grid& grid, const FlowSettings& flow, const SoilSettings& settings);

  // Obstacles and terrain (mesh/obstacles.hpp): the mask of blocked cells, kept by the caller; set
  // before initialise(). A blocked cell holds no soil; its faces to open cells are walls.
  void set_blocked(const Field* mask) { blocked_ = mask; }
  // Obstacles of their own friction against the soil: each blocked cell's obstacle, one plus its index
  // (mark_obstacle_index, kept by the caller), and each obstacle's friction (none: its faces hold the
  // soil as its own strength does).
  void set_obstacle_friction(const Field* obstacle_index, const std::vector<std::optional<rheology::WallFriction>>& friction);
  // Soil fraction from the initial shapes (none in blocked cells).
  void initialise();
  // Properties for the flow solver: density and viscosity of the mixture ([VoF] Eq. 1 or App. A),
  // with the granular viscosity of the soil from the current strain rate and pressure.
  void update_properties(FlowSolver& flow) const;
  // Face viscosities from the face pressure (soil.yield_pressure = "face").
  void update_face_viscosity(FlowSolver& flow) const;
  // Advects c over dt with the flow's (divergence-free) face velocities, in as many sub-steps as the
  // interface Courant limit needs. When the flow carries mass transport (FlowSolver::
  // enable_mass_transport), also gives it the mixture density before the step and the mass each face
  // carried: air and soil volumes as the sweeps moved them, times their densities.
  void advect(FlowSolver& flow, double dt);
  // Refreshes what depends on c alone (the overburden pressure), after initialise() or advect().
  void refresh(const FlowSolver& flow);
  // Eulerian displacement ([VoF] Eq. 16) with the soil velocity c v, explicit upwind, in as many
  // sweeps as keep it stable over dt.
  void transport_displacement(const FlowSolver& flow, double dt);
  // Largest Courant number of one VoF sweep for a step dt, over the faces that can carry soil in
  // `substeps` sub-steps: those within that many cells of more than round-off of it (interface::soil_region).
  double interface_courant(const FlowSolver& flow, double dt, int substeps = 1) const;

  // Diagnostic fields at output: ||D|| ([YS] Eq. 8), Lode angle in degrees, strain norm.
  void compute_diagnostics(const FlowSolver& flow);
  // Volumes, energies and the dissipation rate now; also refreshes the per-cell dissipation and its
  // Lode-angle bins, which accumulate_lode_energy(dt) then adds up over the step.
  SoilBudget budget(const FlowSolver& flow);
  void accumulate_lode_energy(double dt);
  // Dissipated energy so far, binned by Lode angle ([YS] Fig. 17), summed over ranks (collective).
  rheology::LodeHistogram lode_energy() const;
  // The soil's (cells with c >= 0.5) largest displacement and largest speed now, on every rank
  // (collective); 0 where the grid holds no such cell.
  double largest_displacement() const;
  double largest_speed(const FlowSolver& flow) const;
  // The displacement past which the soil counts as having moved: a tenth of the smallest cell (the
  // failure of a stability trial by default; where time.rest_speed starts to look for rest).
  double moved_distance() const { return 0.1 * grid_.min_spacing(); }

  // Soil materials ([[soil.materials]]): how many besides the rheology's own, and the share of each
  // cell's soil that material k (1 .. material_count()) holds. None without materials.
  int material_count() const { return int(share_.size()); }
  const Field& material_share(int k) const { return *share_[k - 1]; }
  const std::string& material_name(int k) const { return settings_.materials[k - 1].name; }
  // The soil volume of each material now, the rheology's own first, in open cells (collective).
  std::vector<double> material_volumes() const;

  Field& soil_fraction() { return *c_; }
  const Field& soil_fraction() const { return *c_; }
  const Field& displacement(int axis) const { return *disp_[axis]; }
  int dimension() const { return grid_.dimension(); }
  const Field& strain_norm() const { return *strain_norm_; }
  const Field& strain_rate_norm() const { return *rate_norm_; }
  const Field& lode_angle() const { return *lode_; }
  const Field& stress_ratio_to_drucker_prager() const { return *stress_ratio_; }
  // The soil's shear stress over its strength (GranularRheology::relative_shear_stress); 1 without a rheology.
  const Field& relative_shear_stress() const { return *relative_stress_; }
  const Field& dissipation() const { return *dissipation_; }  // per cell, from the last budget()
  const SoilSettings& settings() const { return settings_; }
  // The cells within `reach` cells of a cell whose |c| exceeds `floor` (1 there, else 0), ghosts
  // filled. Scratch storage: valid until the next call.
  const Field& soil_region(int reach, double floor = 0.0) const;

 private:
  void fill_fraction_ghosts(Field& f) const;
 public:
  // Snapshot of c and the displacement, for a step taken again (FlowSolver::save_state).
  void save_state();
  void restore_state();
  // No soil and no displacement in the blocked cells' global values, after they were read from local ones.
  void clear_blocked_cells();
  // What a checkpoint holds: c and the displacement; the sweep parity, and this rank's shares of the
  // outflow and of the dissipated energy by Lode angle, as numbers.
  std::vector<Field*> checkpoint_fields() { return state_fields(); }
  std::string checkpoint_field_names() const;  // of checkpoint_fields()
  CheckpointScalars checkpoint_scalars() const;
  // Throws CheckpointError where the numbers are not this soil's.
  void restore_scalars(std::span<const double> shared, std::span<const double> summed);
  // Throws CheckpointError, on every rank, where a restored soil fraction lies outside [0, 1] by more
  // than the sweeps' round-off (collective).
  void check_restored_fraction() const;
 private:
  void fill_displacement_ghosts();
  std::vector<Field*> state_fields();  // what a step changes: c, the displacement, the materials' shares
  void fill_share_ghosts(Field& f, int material) const;  // material: the share's, 1 for share_[0]
  void fill_share_ghosts(std::vector<std::unique_ptr<Field>>& shares) const {  // one set of shares
    for (size_t k = 0; k < shares.size(); ++k) fill_share_ghosts(*shares[k], int(k) + 1);
  }
  void initialise_materials();
  // One directional sweep of c (from -> to) and, with materials, of their shares (share_ / share_tmp_
  // as from_shares says); adds the soil each face carried to soil_through when given.
  // With soils of several densities, also adds the soil's mass each face carried to soil_mass_through.
  void sweep(int axis, double dt, const Field& from, Field& to, bool from_shares, double** soil_through,
             double** soil_mass_through, const double* const* face_velocity);
  interface::RadialWeights radial_weights() const { return {grid_.radius_face_data(), grid_.radius_centre_data()}; }
  // The domain's cells for the sweeps: the ghosts beyond a boundary are boundary ghosts.
  interface::DomainCells domain_cells() const { return {grid_.nx(), grid_.ny(), grid_.periodic_x()}; }
  double compute_dissipation(const FlowSolver& flow);
  double convected_energy_rate(const FlowSolver& flow) const;  // this rank's share (SoilBudget)
  double mixture_viscosity(double c, double pressure, const rheology::StrainRate& rate,
                           const double* shares = nullptr) const;
  // ... on the face of a wall normal to `wall_axis`, the soil's shear against it read from wall_rate.
  double wall_mixture_viscosity(double c, double pressure, const rheology::StrainRate& rate, const double* shares,
                                const BoundaryCondition& wall, const rheology::StrainRate& wall_rate,
                                int wall_axis) const;
  // The shares of the materials in cell (i, j), or (i, j, k) on a mesh of layers (arrays of share_).
  using Shares = rheology::SoilMaterials::Shares;
  void cell_shares(const std::deque<ConstFieldArray>& m, int i, int j, Shares& out) const {
    cell_shares(m, i, j, 0, out);
  }
  void cell_shares(const std::deque<ConstFieldArray>& m, int i, int j, int k, Shares& out) const;
  std::deque<ConstFieldArray> share_arrays(bool ghosted) const;
  // The viscosity of a face of soil fraction cf between cells of c_low and c_high and shares own and
  // other (used only with materials), the weaker side's between two soils.
  double face_mixture_viscosity(double c_low, double c_high, double cf, double pressure,
                                const rheology::StrainRate& rate, const Shares& own, const Shares& other) const;
  double cell_yield_pressure(double cell_pressure, const ConstFieldArray* overburden, int i, int j) const;
  std::unique_ptr<ConstFieldArray> overburden_if_floor() const;
  // Density of a mixture at soil fraction c ([VoF] Eq. 1 or App. A), of the soil's own density or of
  // rho_s given.
  double mixture_density(double c) const {
    return settings_.density_mixing(c, settings_.air_density, settings_.soil_density);
  }
  double mixture_density(double c, double soil_density) const {
    return settings_.density_mixing(c, settings_.air_density, soil_density);
  }
  // The mass flux of a face of velocity u through which the soil volume `soil` per unit area crossed
  // over the step dt (and, with soils of several densities, the soil mass `soil_mass`): u rho(c_swept),
  // the mixture density of what crossed, c_swept = soil / (u dt) (soil_advection.cpp says why). With
  // several densities rho_s is the crossing soil's, its mass over its volume within the lightest and
  // heaviest soil's: sweeps that carried soil back and forth can leave a net volume of round-off beside
  // a net mass that is not.
  double face_mass_flux(double u, double soil, double soil_mass, double dt) const;
  // Whether the soils differ in density (SoilSettings::materials_differ_in_density).
  bool densities_differ() const { return !soil_densities_.empty(); }
  // rho_s of soil shared out as `shares` among the materials: the mean of their densities weighted by
  // their shares (the base holds the rest). With one density, the soil's own.
  double soil_density(const Shares& shares) const {
    double rest = 1.0, rho = 0.0;
    for (size_t k = 1; k < soil_densities_.size(); ++k) {
      const double share = std::clamp(shares[k - 1], 0.0, 1.0);
      rho += share * soil_densities_[k];
      rest -= share;
    }
    return rest > 0.0 ? rho + rest * settings_.soil_density : rho;
  }
  // rho_s of cell (i, j, k)'s soil (arrays of share_; soil.density where all soils share it).
  double cell_soil_density(const std::deque<ConstFieldArray>& m, int i, int j, int k = 0) const {
    if (!densities_differ()) return settings_.soil_density;
    Shares shares{};
    cell_shares(m, i, j, k, shares);
    return soil_density(shares);
  }

  const Grid& grid_;
  const FlowSettings& flow_settings_;
  SoilSettings settings_;
  double ambient_pressure_;  // the yield stress takes the pressure in excess of it (solver/boundary.hpp)
  FieldSnapshot saved_;
  int saved_parity_ = 0;
  double outflow_ = 0.0, saved_outflow_ = 0.0;  // this rank's soil volume carried out of the domain
  // Periodic x: this rank's share of (rho_s - rho_a) L V summed over the soil volumes V carried east
  // through the join (L the strip's length), which the soil's first moment along x loses as the soil
  // comes in at the other end; budget() adds it back, so the potential energy of a slope runs on.
  double join_moment_ = 0.0, saved_join_moment_ = 0.0;
  std::optional<rheology::GranularRheology> rheology_;
  std::optional<rheology::SoilMaterials> materials_;  // with [[soil.materials]]
  std::vector<std::unique_ptr<Field>> share_, share_tmp_, share_start_;
  std::unique_ptr<Field> face_soil_[3];  // one sweep's soil volume per unit face area, with materials
  // Soils of several densities: rho_s of each, the base's first (empty with one density); the density
  // of the soil each face carried in one sweep, and the soil's mass through each face over a step.
  std::vector<double> soil_densities_;
  double lightest_soil_ = 0.0, heaviest_soil_ = 0.0;  // of soil_densities_ and soil.density
  std::unique_ptr<Field> face_soil_density_[3], soil_mass_through_[3];
  std::unique_ptr<Field> c_, c_tmp_, dilatation_;
  std::unique_ptr<Field> region_[2];  // scratch of soil_region
  std::unique_ptr<Field> disp_[3], disp_new_[3];  // [2] on a mesh of layers
  std::unique_ptr<Field> strain_norm_, rate_norm_, lode_, stress_ratio_, relative_stress_, dissipation_;
  rheology::LodeHistogram lode_rate_, lode_energy_;  // this rank's cells: W and J per bin
  std::unique_ptr<Field> overburden_;  // rho_s g times the soil depth above each centre (Pa)
  std::unique_ptr<ColumnDepth> column_depth_;  // made at the first overburden (collective)
  void compute_overburden(const std::array<double, 3>& gravity);
  // Sets c to 0 on the owned cells whose soil is round-off (interface::round_off_soil) and refreshes its
  // ghosts: after the initial shapes and after each advection.
  void clear_round_off_soil();
  // On a mesh of layers (soil_phase_3d.cpp): the public operations' 3D forms.
  void initialise_3d();
  void initialise_materials_3d();
  void update_properties_3d(FlowSolver& flow) const;
  void update_face_viscosity_3d(FlowSolver& flow) const;
  double interface_courant_3d(const FlowSolver& flow, double dt) const;
  void advect_3d(FlowSolver& flow, double dt);
  void compute_diagnostics_3d(const FlowSolver& flow);
  double compute_dissipation_3d(const FlowSolver& flow);
  SoilBudget budget_3d(const FlowSolver& flow);
  double largest_magnitude_over_soil(const Field* const components[3]) const;
  int sweep_parity_ = 0;
  const Field* blocked_ = nullptr;
  const Field* obstacle_index_ = nullptr;       // with obstacles of their own friction
  std::vector<BoundaryCondition> obstacle_walls_;  // each obstacle's faces as a wall, by index
};

}  // namespace granflow

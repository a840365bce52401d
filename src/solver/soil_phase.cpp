#include "solver/soil_phase.hpp"

#include "io/checkpoint.hpp"
#include "io/collective_failure.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/gather.hpp"
#include "mesh/obstacles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>

#include "models/interface/material_transport.hpp"
#include "models/interface/vof_advection.hpp"
#include "models/interface/wetted_fraction.hpp"
#include "models/rheology/invariants.hpp"
#include "solver/cell_faces.hpp"
#include "solver/divergence_error.hpp"
#include "operators/face_interpolation.hpp"
#include "operators/strain_rate.hpp"

namespace granflow {

// The rheology's and the transport's bounds on the number of soil materials are one bound.
static_assert(rheology::SoilMaterials::max_count == interface::max_materials);

SoilPhase::SoilPhase(const Grid& grid, const FlowSettings& flow, const SoilSettings& settings)
    : grid_(grid), flow_settings_(flow), settings_(settings), ambient_pressure_(ambient_pressure(flow.boundaries)) {
  if (settings.rheology) rheology_.emplace(*settings.rheology);
  auto make = [&] { return std::make_unique<Field>(grid); };
  if (!settings.materials.empty()) {
    std::vector<rheology::RheologyParameters> rheologies;
    for (const auto& m : settings.materials) rheologies.push_back(m.rheology);
    materials_.emplace(settings.rheology.value(), rheologies);
    for (size_t k = 0; k < settings.materials.size(); ++k) {
      for (auto* list : {&share_, &share_tmp_, &share_start_}) {
        list->push_back(make());
        list->back()->set(0.0);
      }
    }
    for (auto& f : face_soil_) {
      f = make();
      f->set(0.0);
    }
    if (settings.materials_differ_in_density()) {
      soil_densities_.push_back(settings.soil_density);
      for (const auto& m : settings.materials) soil_densities_.push_back(m.rheology.density);
      for (int a = 0; a < 2; ++a) {
        face_soil_density_[a] = make();
        face_soil_density_[a]->set(0.0);
        soil_mass_through_[a] = make();
        soil_mass_through_[a]->set(0.0);
      }
    }
  }
  c_ = make();
  c_tmp_ = make();
  dilatation_ = make();
  region_[0] = make();
  region_[1] = make();
  strain_norm_ = make();
  overburden_ = make();
  rate_norm_ = make();
  lode_ = make();
  stress_ratio_ = make();
  dissipation_ = make();
  for (int a = 0; a < 2; ++a) {
    disp_[a] = make();
    disp_new_[a] = make();
    disp_[a]->set(0.0);
  }
  for (Field* f : {c_.get(), c_tmp_.get(), dilatation_.get(), region_[0].get(), region_[1].get(), strain_norm_.get(), rate_norm_.get(), lode_.get(), stress_ratio_.get(), dissipation_.get(),
                   overburden_.get()})
    f->set(0.0);
}

std::vector<Field*> SoilPhase::state_fields() {
  std::vector<Field*> fields{c_.get(), disp_[0].get(), disp_[1].get()};
  for (auto& f : share_) fields.push_back(f.get());
  return fields;
}

std::string SoilPhase::checkpoint_field_names() const {
  std::string names = "c displacement_x displacement_y";
  for (const auto& m : settings_.materials) names += " share_" + m.name;
  return names;
}

void SoilPhase::save_state() {
  saved_.save(state_fields());
  saved_parity_ = sweep_parity_;
  saved_outflow_ = outflow_;
  saved_join_moment_ = join_moment_;
}

CheckpointScalars SoilPhase::checkpoint_scalars() const {
  CheckpointScalars v{{double(sweep_parity_)}, {outflow_}};
  v.summed.insert(v.summed.end(), lode_energy_.values().begin(), lode_energy_.values().end());
  v.summed.push_back(join_moment_);
  return v;
}

void SoilPhase::restore_scalars(std::span<const double> shared, std::span<const double> summed) {
  const size_t bins = lode_energy_.values().size();
  // Checkpoints written before the join's moment was kept end after the Lode bins.
  if (shared.size() != 1 || (summed.size() != 2 + bins && summed.size() != 1 + bins))
    throw CheckpointError("the checkpoint's state does not match this case's model");
  sweep_parity_ = int(shared[0]);
  outflow_ = summed[0];
  std::copy(summed.begin() + 1, summed.begin() + 1 + long(bins), lode_energy_.values().begin());
  join_moment_ = summed.size() == 2 + bins ? summed[1 + bins] : 0.0;
}

void SoilPhase::check_restored_fraction() const {
  // The sweeps keep c within [0, 1] to round-off (1e-15 in the advection tests); a checkpoint's c
  // beyond this margin was damaged after it was written, and would run on with soil made or lost.
  constexpr double margin = 1e-6;
  std::string problem;
  const ConstFieldArray c(grid_.field_dm(), c_->global());
  const auto& b = grid_.owned();
  for (int j = b.ys; j < b.ye() && problem.empty(); ++j)
    for (int i = b.xs; i < b.xe(); ++i)
      if (!(c[j][i] >= -margin && c[j][i] <= 1 + margin)) {
        problem = fmt::format("the checkpoint is damaged: its soil fraction c is {} in cell ({}, {}), outside [0, 1]",
                              c[j][i], i, j);
        break;
      }
  if (auto text = first_failure(grid_.comm(), problem); !text.empty()) throw CheckpointError(text);
}

void SoilPhase::clear_blocked_cells() {
  if (!blocked_) return;
  for (auto* f : {disp_[0].get(), disp_[1].get()}) zero_blocked_cells(grid_, blocked_, *f);
  fill_fraction_ghosts(*c_);  // zeroes c there, and mirrors anew
  for (auto& f : share_) fill_share_ghosts(*f);
}

void SoilPhase::restore_state() {
  saved_.restore(state_fields());
  clear_blocked_cells();
  sweep_parity_ = saved_parity_;
  outflow_ = saved_outflow_;
  join_moment_ = saved_join_moment_;
}

void SoilPhase::initialise() {
  {
    FieldArray c(grid_.field_dm(), c_->global());
    const interface::ShapeUnion initial_soil(settings_.initial_soil);
    const auto& b = grid_.owned();
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        const double x0 = grid_.xc(i) - 0.5 * grid_.dx(i), y0 = grid_.yc(j) - 0.5 * grid_.dy(j);
        c[j][i] = initial_soil.fraction(x0, x0 + grid_.dx(i), y0, y0 + grid_.dy(j), grid_.axisymmetric());
      }
  }
  fill_fraction_ghosts(*c_);
  if (materials_) initialise_materials();
}

// Each material's share of a cell's soil, by samples x samples midpoint sampling: a sample in the
// shapes' union belongs to the last shape listed that holds it (weighted by its radius when
// axisymmetric, as the soil fraction's samples are).
void SoilPhase::initialise_materials() {
  constexpr int samples = 16;
  const interface::ShapeUnion shapes(settings_.initial_soil);
  const auto& b = grid_.owned();
  ConstFieldArray c(grid_.field_dm(), c_->global());
  std::vector<std::unique_ptr<FieldArray>> m;
  for (auto& f : share_) m.push_back(std::make_unique<FieldArray>(grid_.field_dm(), f->global()));
  const int count = int(share_.size());
  const int shape_count = int(settings_.initial_soil.size());
  std::vector<double> weight(size_t(count) + 1);
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      for (int k = 0; k < count; ++k) (*m[k])[j][i] = 0.0;
      if (!(c[j][i] > 0.0)) continue;
      std::fill(weight.begin(), weight.end(), 0.0);
      const double x0 = grid_.xc(i) - 0.5 * grid_.dx(i), y0 = grid_.yc(j) - 0.5 * grid_.dy(j);
      for (int sy = 0; sy < samples; ++sy)
        for (int sx = 0; sx < samples; ++sx) {
          const double x = x0 + (sx + 0.5) * grid_.dx(i) / samples, y = y0 + (sy + 0.5) * grid_.dy(j) / samples;
          for (int shape = shape_count - 1; shape >= 0; --shape)
            if (shapes.shape_contains(size_t(shape), x, y)) {
              weight[size_t(settings_.initial_material[size_t(shape)])] += grid_.axisymmetric() ? x : 1.0;
              break;
            }
        }
      double total = 0.0;
      for (double w : weight) total += w;
      if (total > 0.0)
        for (int k = 0; k < count; ++k) (*m[k])[j][i] = weight[size_t(k) + 1] / total;
      else  // soil the samples missed (a sliver of a cell): the material of the last shape that overlaps the cell
        for (int shape = shape_count - 1; shape >= 0; --shape)
          if (interface::overlaps(settings_.initial_soil[size_t(shape)], {x0, y0}, {x0 + grid_.dx(i), y0 + grid_.dy(j)})) {
            const int k = settings_.initial_material[size_t(shape)];
            if (k > 0) (*m[k - 1])[j][i] = 1.0;
            break;
          }
    }
  m.clear();
  for (auto& f : share_) fill_share_ghosts(*f);
}

// Ghosts of a material share: walls mirror (zero gradient), blocked cells hold none; soil coming in
// through an atmosphere side is the rheology's own (share 0).
void SoilPhase::fill_share_ghosts(Field& f) const {
  zero_blocked_cells(grid_, blocked_, f);
  fill_copied_ghosts(f);
  FieldArray a(grid_.field_dm(), f.local());
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny(), gw = Grid::ghost_width;
  auto open = [&](Side side) { return boundary(flow_settings_.boundaries, side).kind == BoundaryKind::atmosphere; };
  for (int k = 1; k <= gw; ++k)
    for (int j = b.ys - gw; j < b.ye() + gw; ++j) {
      if (grid_.owns_boundary(Side::west) && open(Side::west)) a[j][-k] = 0.0;
      if (grid_.owns_boundary(Side::east) && open(Side::east)) a[j][nx - 1 + k] = 0.0;
    }
  for (int k = 1; k <= gw; ++k)
    for (int i = b.xs - gw; i < b.xe() + gw; ++i) {
      if (b.ys == 0 && open(Side::south)) a[-k][i] = 0.0;
      if (b.ye() == ny && open(Side::north)) a[ny - 1 + k][i] = 0.0;
    }
}

// Ghosts that copy the nearest cell at the domain's sides and mirror the open cells in blocked ones.
void SoilPhase::fill_copied_ghosts(Field& f) const {
  f.scatter_to_local();
  FieldArray a(grid_.field_dm(), f.local());
  mirror_into_blocked(grid_, BlockedView(grid_, blocked_).data(), a.data(), 1.0);
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny(), gw = Grid::ghost_width;
  for (int k = 1; k <= gw; ++k)
    for (int j = b.ys - gw; j < b.ye() + gw; ++j) {
      if (grid_.owns_boundary(Side::west)) a[j][-k] = a[j][0];
      if (grid_.owns_boundary(Side::east)) a[j][nx - 1 + k] = a[j][nx - 1];
    }
  for (int k = 1; k <= gw; ++k)
    for (int i = b.xs - gw; i < b.xe() + gw; ++i) {
      if (b.ys == 0) a[-k][i] = a[0][i];
      if (b.ye() == ny) a[ny - 1 + k][i] = a[ny - 1][i];
    }
}

std::deque<ConstFieldArray> SoilPhase::share_arrays(bool ghosted) const {
  std::deque<ConstFieldArray> arrays;
  for (const auto& f : share_) arrays.emplace_back(grid_.field_dm(), ghosted ? f->local() : f->global());
  return arrays;
}

void SoilPhase::cell_shares(const std::deque<ConstFieldArray>& m, int i, int j, Shares& out) const {
  for (size_t k = 0; k < m.size(); ++k) out[k] = m[k][j][i];
}

// Ghosts of c: soil carried in through an atmosphere boundary has the boundary's inflow fraction;
// walls mirror, which gives interface normals meeting a wall at right angles.
void SoilPhase::fill_fraction_ghosts(Field& f) const {
  zero_blocked_cells(grid_, blocked_, f);  // no soil in a blocked cell (a sweep leaves there the mirror it read)
  const BlockedView mask(grid_, blocked_);
  f.scatter_to_local();
  FieldArray a(grid_.field_dm(), f.local());
  mirror_into_blocked(grid_, mask.data(), a.data(), 1.0);  // an obstacle's walls mirror, as the domain's
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny(), gw = Grid::ghost_width;
  auto value = [&](Side s, double mirror) {
    const auto& bc = boundary(flow_settings_.boundaries, s);
    return bc.kind == BoundaryKind::atmosphere ? bc.inflow_soil_fraction : mirror;
  };
  for (int k = 1; k <= gw; ++k)
    for (int j = b.ys - gw; j < b.ye() + gw; ++j) {
      if (grid_.owns_boundary(Side::west)) a[j][-k] = value(Side::west, a[j][k - 1]);
      if (grid_.owns_boundary(Side::east)) a[j][nx - 1 + k] = value(Side::east, a[j][nx - k]);
    }
  for (int k = 1; k <= gw; ++k)
    for (int i = b.xs - gw; i < b.xe() + gw; ++i) {
      if (b.ys == 0) a[-k][i] = value(Side::south, a[k - 1][i]);
      if (b.ye() == ny) a[ny - 1 + k][i] = value(Side::north, a[ny - k][i]);
    }
}

void SoilPhase::fill_displacement_ghosts() {
  for (auto& d : disp_) fill_copied_ghosts(*d);
}

// Viscosity of a mixture at soil fraction c: the soil's from the rheology at the given pressure (its
// excess over the ambient pressure) and strain rate (or its Newtonian value), mixed with the air's.
double SoilPhase::mixture_viscosity(double c, double pressure, const rheology::StrainRate& rate,
                                    const double* shares) const {
  const auto& s = settings_;
  const double mu_soil = !rheology_ || !(c > 0.0) ? s.soil_viscosity
                         : shares ? materials_->dynamic_viscosity(rate, pressure - ambient_pressure_, shares)
                                  : rheology_->dynamic_viscosity(rate, pressure - ambient_pressure_);
  return s.viscosity_mixing(c, s.air_viscosity, mu_soil);
}

void SoilPhase::set_obstacle_friction(const Field* obstacle_index,
                                      const std::vector<std::optional<rheology::WallFriction>>& friction) {
  obstacle_index_ = obstacle_index;
  obstacle_walls_.assign(friction.size(), obstacle_wall);
  for (size_t k = 0; k < friction.size(); ++k) obstacle_walls_[k].friction = friction[k];
}

// ... on the face of a wall: where the wall has a friction of its own, the soil there is no stronger
// than the wall lets it be, the wall's strength at the wall's pressure regularised at the soil's
// shear against the wall, wall_rate.xy (models/rheology/wall_friction.hpp).
double SoilPhase::wall_mixture_viscosity(double c, double pressure, const rheology::StrainRate& rate,
                                         const double* shares, const BoundaryCondition& wall,
                                         const rheology::StrainRate& wall_rate) const {
  if (!wall.friction || !rheology_ || !(c > 0.0)) return mixture_viscosity(c, pressure, rate, shares);
  const double p = pressure - ambient_pressure_;
  const double own = shares ? materials_->dynamic_viscosity(rate, p, shares) : rheology_->dynamic_viscosity(rate, p);
  const double slide = rheology_->regularise(wall.friction->shear_strength(p), std::abs(wall_rate.xy));
  return settings_.viscosity_mixing(c, settings_.air_viscosity, std::min(own, slide));
}

// The pressure a cell's yield stress takes: its own, or under soil.yield_pressure = "lithostatic_floor"
// at least the weight of the soil above it (overburden: that field's array, null otherwise).
double SoilPhase::cell_yield_pressure(double cell_pressure, const ConstFieldArray* overburden, int i, int j) const {
  return overburden ? std::max(cell_pressure, ambient_pressure_ + (*overburden)[j][i]) : cell_pressure;
}

std::unique_ptr<ConstFieldArray> SoilPhase::overburden_if_floor() const {
  if (settings_.yield_pressure != YieldPressure::lithostatic_floor) return nullptr;
  return std::make_unique<ConstFieldArray>(grid_.field_dm(), overburden_->global());
}

void SoilPhase::update_properties(FlowSolver& flow) const {
  const auto& b = grid_.owned();
  ConstFieldArray c(grid_.field_dm(), c_->global());
  ConstFieldArray u = local_read(grid_, flow.velocity(0)), v = local_read(grid_, flow.velocity(1));
  ConstFieldArray p(grid_.field_dm(), flow.pressure().global());
  FieldArray rho(grid_.field_dm(), flow.density().global()), mu(grid_.field_dm(), flow.viscosity().global());
  const auto overburden = overburden_if_floor();
  const auto m = share_arrays(false);
  Shares shares{};
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const double cc = c[j][i];
      if (materials_) cell_shares(m, i, j, shares);
      rho[j][i] = densities_differ() ? mixture_density(cc, soil_density(shares)) : mixture_density(cc);
      mu[j][i] = mixture_viscosity(cc, cell_yield_pressure(p[j][i], overburden.get(), i, j),
                                   cell_strain_rate(grid_, u.data(), v.data(), i, j), materials_ ? shares.data() : nullptr);
    }
}

// Face viscosities with the yield stress taken at the face ([VoF] Eqs. 8-9 with p on the face): each
// side is the mixture of its own cell (its c and D) at the face's pressure, and the face takes their
// mean as the operator does for cell values. Fills the faces of owned cells, including those shared
// with the ghost column or row on the low side, so that the operator needs no exchange. Needs the
// ghosts of c and p (current after the advection and the pressure solve).
void SoilPhase::update_face_viscosity(FlowSolver& flow) const {
  const auto kind = flow_settings_.numerics.face_viscosity;
  const auto& g = flow_settings_.gravity;
  const bool at_face = settings_.strain_rate == StrainRateAt::face;
  const bool face_fraction = settings_.face_fraction == FaceFraction::face;
  const bool quadratic_wall = flow_settings_.numerics.quadratic_wall_gradient;
  ConstFieldArray c = local_read(grid_, *c_);
  ConstFieldArray u = local_read(grid_, flow.velocity(0)), v = local_read(grid_, flow.velocity(1));
  ConstFieldArray p = local_read(grid_, flow.pressure()), rho = local_read(grid_, flow.density());
  // With soil materials: the shares of a cell (own, other) and of a face (both), null without.
  const auto m = share_arrays(true);
  std::optional<ConstFieldArray> obstacle_of;  // which obstacle a blocked cell belongs to
  if (obstacle_index_) obstacle_of.emplace(grid_.field_dm(), obstacle_index_->local());
  Shares own{}, other{};
  const double* own_shares = materials_ ? own.data() : nullptr;
  const double* other_shares = materials_ ? other.data() : nullptr;
  // One evaluation on the face at soil fraction cf. Between two soils the face is as strong as the
  // weaker side: a slip surface along the contact of two materials runs on the weaker one's side (with
  // the mean of their strengths a slip along a stiff foundation had to run a cell higher). A side
  // without soil, or with a sliver whose shares are round-off, has no shares to give.
  auto on_face = [&](int i, int j, int in, int jn, double cf, double pressure, const rheology::StrainRate& rate) {
    if (!materials_) return mixture_viscosity(cf, pressure, rate);
    if (!(c[jn][in] > interface::no_soil)) return mixture_viscosity(cf, pressure, rate, own_shares);
    if (!(c[j][i] > interface::no_soil) || own == other) return mixture_viscosity(cf, pressure, rate, other_shares);
    return std::min(mixture_viscosity(cf, pressure, rate, own_shares), mixture_viscosity(cf, pressure, rate, other_shares));
  };
  // Face (axis, i, j) lies between cell (i, j) and its neighbour at +1 along axis.
  auto face = [&](int axis, int i, int j, double pressure) {
    const int in = i + (axis == 0), jn = j + (axis == 1);
    if (c[j][i] == 0.0 && c[jn][in] == 0.0) {  // air on both sides: its viscosity, which reads no strain rate
      const double air = mixture_viscosity(0.0, pressure, rheology::StrainRate{});
      return at_face ? air : face_mean(kind, air, air);
    }
    if (materials_) {
      cell_shares(m, i, j, own);
      cell_shares(m, in, jn, other);
    }
    if (at_face) {
      const auto rate = face_strain_rate(grid_, u.data(), v.data(), axis, i, j);
      // One evaluation at the face's soil fraction; also where both sides hold the same mixture (the bulk).
      if (face_fraction || c[jn][in] == c[j][i])
        return on_face(i, j, in, jn, 0.5 * (c[j][i] + c[jn][in]), pressure, rate);
      return face_mean(kind, mixture_viscosity(c[j][i], pressure, rate, own_shares),
                       mixture_viscosity(c[jn][in], pressure, rate, other_shares));
    }
    return face_mean(kind, mixture_viscosity(c[j][i], pressure, cell_strain_rate(grid_, u.data(), v.data(), i, j), own_shares),
                     mixture_viscosity(c[jn][in], pressure, cell_strain_rate(grid_, u.data(), v.data(), in, jn), other_shares));
  };
  fill_owned_faces(
      grid_, flow.face_viscosity(0), flow.face_viscosity(1),
      [&](int axis, int i, int j) {
        const int in = i + (axis == 0), jn = j + (axis == 1);
        return face(axis, i, j, 0.5 * (p[j][i] + p[jn][in]));
      },
      [&](int axis, int i, int j, int sign) {  // the cell's pressure carried hydrostatically to the wall
        const int in = i + (axis == 0 ? sign : 0), jn = j + (axis == 1 ? sign : 0);
        const bool obstacle = !grid_.outside(in, jn);  // a blocked neighbour
        const double half = 0.5 * sign * (axis == 0 ? grid_.dx(i) : grid_.dy(j));
        const double pressure = p[j][i] + rho[j][i] * g[axis] * half;
        if (materials_) cell_shares(m, i, j, own);
        const int obstacle_index = obstacle && obstacle_of ? int((*obstacle_of)[jn][in]) : 0;
        const auto& bc = !obstacle            ? boundary(flow_settings_.boundaries, side_of(axis, sign))
                         : obstacle_index > 0 ? obstacle_walls_[size_t(obstacle_index - 1)]
                                              : obstacle_wall;
        // The face between the ghost and the cell, the ghost's velocity encoding the wall.
        const int il = sign < 0 ? i - (axis == 0) : i, jl = sign < 0 ? j - (axis == 1) : j;
        auto wall_rate = [&] {
          return quadratic_wall && bc.kind != BoundaryKind::atmosphere
                     ? quadratic_wall_strain_rate(grid_, u.data(), v.data(), axis, i, j, sign, bc.wall_velocity,
                                                  bc.kind == BoundaryKind::slip)
                     : face_strain_rate(grid_, u.data(), v.data(), axis, il, jl);
        };
        if (at_face) {
          // The face's own soil fraction: how much of it the cell's soil covers. A film on the floor
          // covers all of the floor under it, so the floor rubs on soil, not on the air mixture.
          const double cf = face_fraction ? interface::wetted_side_fraction(c.data(), grid_.dx_data(), grid_.dy_data(),
                                                                            i, j, axis, sign, grid_.radius_centre_data())
                                          : c[j][i];
          const auto rate = wall_rate();
          return wall_mixture_viscosity(cf, pressure, rate, own_shares, bc, rate);
        }
        const auto cell_rate = cell_strain_rate(grid_, u.data(), v.data(), i, j);
        if (!bc.friction) return mixture_viscosity(c[j][i], pressure, cell_rate, own_shares);
        return wall_mixture_viscosity(c[j][i], pressure, cell_rate, own_shares, bc, wall_rate());
      },
      BlockedView(grid_, blocked_).data());
}

void SoilPhase::refresh(const FlowSolver& flow) {
  if (settings_.yield_pressure == YieldPressure::lithostatic_floor) compute_overburden(flow.settings().gravity);
}

// Depth of soil above each cell centre, sum of c dy over the cells above plus half the cell's own,
// times rho_s |g|. Columns cross ranks, so the soil fraction is gathered whole (once per step).
void SoilPhase::compute_overburden(const std::array<double, 2>& gravity) {
  // Soils of several densities: the column's mass per area, c rho_s / soil.density in place of c.
  if (densities_differ()) {
    FieldArray o(grid_.field_dm(), overburden_->global());
    ConstFieldArray cf(grid_.field_dm(), c_->global());
    const auto m = share_arrays(false);
    const auto& ob = grid_.owned();
    for (int j = ob.ys; j < ob.ye(); ++j)
      for (int i = ob.xs; i < ob.xe(); ++i) o[j][i] = cf[j][i] * cell_soil_density(m, i, j) / settings_.soil_density;
  }
  const std::vector<double> c = gather_to_all(grid_, densities_differ() ? *overburden_ : *c_);
  DM dm = grid_.field_dm();
  const int nx = grid_.nx(), ny = grid_.ny();
  const double weight = settings_.soil_density * std::abs(gravity[1]);
  const auto& b = grid_.owned();
  {
    FieldArray o(dm, overburden_->global());
    for (int i = b.xs; i < b.xe(); ++i) {
      double depth = 0.0;
      for (int j = ny - 1; j >= b.ys; --j) {
        const double cj = c[size_t(j) * nx + i] * grid_.dy(j);
        if (j < b.ye()) o[j][i] = weight * (depth + 0.5 * cj);
        depth += cj;
      }
    }
  }
}

const Field& SoilPhase::soil_region(int reach, double floor) const {
  // c's ghosts are current: every change of c ends with fill_fraction_ghosts. The region's own
  // domain-boundary ghosts stay 0 (set at construction); soil coming in through a boundary is in c's.
  const Field* in = c_.get();
  if (blocked_) {
    // c without the blocked cells' mirrors, nor the wall ghosts that mirror those: they are not
    // soil, and a rank cannot mirror a ghost cell whose open side lies beyond its ghosts, so counting
    // them made the region differ between rank layouts. A wall's ghosts mirror cells whose own 3 x 3
    // boxes count them anyway; an open side's hold the soil coming in, and stay. The first pass reads
    // this copy (region_[1], free until the second pass).
    VecCopy(c_->local(), region_[1]->local());
    FieldArray a(grid_.field_dm(), region_[1]->local());
    const BlockedView mask(grid_, blocked_);
    const auto& b = grid_.owned();
    const int gw = Grid::ghost_width, ny = grid_.ny();
    auto open_side = [&](Side side) { return boundary(flow_settings_.boundaries, side).kind == BoundaryKind::atmosphere; };
    for (int j = b.ys - gw; j < b.ye() + gw; ++j)
      for (int i = b.xs - gw; i < b.xe() + gw; ++i) {
        const bool outside = grid_.outside(i, j);
        const Side side = j < 0 ? Side::south : j >= ny ? Side::north : i < 0 ? Side::west : Side::east;
        if (is_blocked(mask.data(), i, j) || (outside && !open_side(side))) a[j][i] = 0.0;
      }
    in = region_[1].get();
  }
  for (int k = 0; k < std::max(reach, 1); ++k) {
    Field& out = *region_[k % 2];
    {
      ConstFieldArray a(grid_.field_dm(), in->local());
      FieldArray r(grid_.field_dm(), out.global());
      interface::soil_region(a.data(), grid_.owned(), r.data(), k == 0 ? floor : 0.0);
    }
    out.scatter_to_local();
    if (k == 0 && in == region_[1].get()) {  // the copy's ghosts outside the domain: back to the region's 0
      FieldArray a(grid_.field_dm(), region_[1]->local());
      const auto& b = grid_.owned();
      const int gw = Grid::ghost_width;
      for (int j = b.ys - gw; j < b.ye() + gw; ++j)
        for (int i = b.xs - gw; i < b.xe() + gw; ++i)
          if (grid_.outside(i, j)) a[j][i] = 0.0;
    }
    in = &out;
  }
  return *in;
}

double SoilPhase::interface_courant(const FlowSolver& flow, double dt, int substeps) const {
  ConstFieldArray fx = local_read(grid_, flow.face_velocity(0)), fy = local_read(grid_, flow.face_velocity(1));
  ConstFieldArray region(grid_.field_dm(), soil_region(substeps).local());
  const double co = std::max(
      interface::max_sweep_courant(0, dt, fx.data(), grid_.dx_data(), grid_.dy_data(), grid_.owned(), radial_weights(),
                                   region.data()),
      interface::max_sweep_courant(1, dt, fy.data(), grid_.dx_data(), grid_.dy_data(), grid_.owned(), {},
                                   region.data()));
  return mpi_max(grid_.comm(), co);
}

void SoilPhase::advect(FlowSolver& flow, double dt) {
  // A step sized by this limit from these same face velocities lands on it up to round-off, which
  // differs between rank layouts; without the allowance ceil() would take one sweep or two by chance.
  constexpr double allowance = 1e-9;
  auto substeps_for = [&](double co) { return std::max(1, int(std::ceil(co / settings_.interface_courant - allowance))); };
  // The faces that can carry soil depend on how many sub-steps it moves in: widen the region until
  // it covers them (once at most, in practice).
  // Far more sweeps than a step can need means velocities far beyond the step's (a fixed step over a
  // flow that has blown up); the Courant number is the same on every rank, so all stop together.
  // Checked on the widened regions too, where faster air may lie, so the region stays within that reach.
  constexpr double max_substeps = 1000;
  auto sweeps_within_limit = [&](double co) {
    if (!(co / settings_.interface_courant <= max_substeps))
      throw DivergenceError(fmt::format("the soil fraction would need {:.3g} sweeps in a step of {:.3g} s: the flow "
                                        "has diverged (lower time.dt, or let time.adaptive size the step)",
                                        co / settings_.interface_courant, dt));
    return substeps_for(co);
  };
  int substeps = sweeps_within_limit(interface_courant(flow, dt, 1));
  for (int reach = 1; substeps > reach;) {
    reach = substeps;
    substeps = std::max(substeps, sweeps_within_limit(interface_courant(flow, dt, reach)));
  }
  const double h = dt / substeps;
  const auto& b = grid_.owned();
  ConstFieldArray fx = local_read(grid_, flow.face_velocity(0)), fy = local_read(grid_, flow.face_velocity(1));
  const double* const* face[2] = {fx.data(), fy.data()};
  // The soil volume per unit area through each face adds up in the flow's mass fluxes, which become
  // mass fluxes below.
  const bool carry_mass = flow.carries_mass_transport();
  std::optional<FieldArray> soil_through[2], soil_mass_through[2];
  if (carry_mass) {
    {
      ConstFieldArray c(grid_.field_dm(), c_->global());
      FieldArray rho0 = local_array(grid_, flow.start_density());
      const auto m = share_arrays(false);
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          rho0[j][i] = densities_differ() ? mixture_density(c[j][i], cell_soil_density(m, i, j)) : mixture_density(c[j][i]);
    }
    for (int a = 0; a < 2; ++a) {
      flow.mass_flux(a).set(0.0);
      soil_through[a].emplace(grid_.field_dm(), flow.mass_flux(a).local());
      if (densities_differ()) {
        soil_mass_through_[a]->set(0.0);
        soil_mass_through[a].emplace(grid_.field_dm(), soil_mass_through_[a]->local());
      }
    }
  }
  auto mass_through = [&](int axis) { return soil_mass_through[axis] ? soil_mass_through[axis]->data() : nullptr; };
  for (int s = 0; s < substeps; ++s) {
    const int first = sweep_parity_, second = 1 - sweep_parity_;
    sweep_parity_ = 1 - sweep_parity_;  // alternate the sweep order (Strang-like symmetry over two steps)
    {
      ConstFieldArray c(grid_.field_dm(), c_->local());
      FieldArray cc(grid_.field_dm(), dilatation_->local());
      interface::dilatation_indicator(c.data(), b, cc.data());
    }
    // The materials' shares at the start, held with the indicator over both sweeps.
    for (size_t k = 0; k < share_.size(); ++k) VecCopy(share_[k]->global(), share_start_[k]->global());
    sweep(first, h, *c_, *c_tmp_, true, carry_mass ? soil_through[first]->data() : nullptr, mass_through(first),
          face[first]);
    sweep(second, h, *c_tmp_, *c_, false, carry_mass ? soil_through[second]->data() : nullptr, mass_through(second),
          face[second]);
  }
  if (carry_mass) {
    // Mass flux = u rho(c_swept), the mixture density of what crossed the face: c_swept = s / u with s
    // the soil's volume flux per unit area over the step. With the linear mixture that is the phases'
    // own masses, rho_a (u - s) + rho_s s; with the arctan one the mass the time derivative takes
    // (start_density) is the same function of c, so a face fed by a pure cell carries exactly that.
    // Soils of several densities: rho_s is that of the soil that crossed, its mass over its volume,
    // within the lightest and heaviest soil's (sweeps that carried soil back and forth through a face
    // can leave a net volume of round-off beside a net mass that is not).
    double lightest = settings_.soil_density, heaviest = settings_.soil_density;
    for (double rho : soil_densities_) {
      lightest = std::min(lightest, rho);
      heaviest = std::max(heaviest, rho);
    }
    auto to_mass = [&](int axis, const double* const* u, int i, int j) {
      double** m = soil_through[axis]->data();
      const double swept = u[j][i] != 0.0 ? std::clamp(m[j][i] / (dt * u[j][i]), 0.0, 1.0) : 0.0;
      if (!densities_differ()) {
        m[j][i] = u[j][i] * mixture_density(swept);
        return;
      }
      const double soil_mass = (*soil_mass_through[axis])[j][i];
      const double rho_s = m[j][i] != 0.0 ? std::clamp(soil_mass / m[j][i], lightest, heaviest) : settings_.soil_density;
      m[j][i] = u[j][i] * mixture_density(swept, rho_s);
    };
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs - 1; i < b.xe(); ++i) to_mass(0, fx.data(), i, j);
    for (int j = b.ys - 1; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) to_mass(1, fy.data(), i, j);
  }
}

void SoilPhase::sweep(int axis, double dt, const Field& from, Field& to, bool from_shares, double** soil_through,
                      double** soil_mass_through, const double* const* face_velocity) {
  const auto& b = grid_.owned();
  const interface::RadialWeights radial = radial_weights();
  {
    ConstFieldArray c(grid_.field_dm(), from.local());
    ConstFieldArray cc(grid_.field_dm(), dilatation_->local());
    FieldArray c_new(grid_.field_dm(), to.global());
    if (!materials_) {
      interface::vof_sweep(axis, dt, c.data(), face_velocity, cc.data(), grid_.dx_data(), grid_.dy_data(), b, c_new.data(),
                           radial, soil_through, domain_cells());
    } else {
      // The sweep's own face fluxes, which carry the materials' shares, then add up in soil_through.
      FieldArray through(grid_.field_dm(), face_soil_[axis]->local());
      for (int j = b.ys - 1; j < b.ye(); ++j)
        for (int i = b.xs - 1; i < b.xe(); ++i) through[j][i] = 0.0;
      interface::vof_sweep(axis, dt, c.data(), face_velocity, cc.data(), grid_.dx_data(), grid_.dy_data(), b, c_new.data(),
                           radial, through.data(), domain_cells());
      const auto& in = from_shares ? share_ : share_tmp_;
      auto& out = from_shares ? share_tmp_ : share_;
      std::deque<ConstFieldArray> m, m0;
      std::deque<FieldArray> m_new;
      std::vector<const double* const*> m_rows, m0_rows;
      std::vector<double**> m_new_rows;
      for (size_t k = 0; k < share_.size(); ++k) {
        m_rows.push_back(m.emplace_back(grid_.field_dm(), in[k]->local()).data());
        m0_rows.push_back(m0.emplace_back(grid_.field_dm(), share_start_[k]->global()).data());
        m_new_rows.push_back(m_new.emplace_back(grid_.field_dm(), out[k]->global()).data());
      }
      std::optional<FieldArray> face_density;
      if (soil_mass_through) face_density.emplace(grid_.field_dm(), face_soil_density_[axis]->local());
      interface::material_sweep(axis, dt, c.data(), c_new.data(), int(share_.size()), m_rows.data(), m0_rows.data(),
                                face_velocity, through.data(), cc.data(), grid_.dx_data(), grid_.dy_data(), b,
                                m_new_rows.data(), radial, soil_densities_.data(),
                                face_density ? face_density->data() : nullptr);
      if (soil_through) {
        // The faces bounding owned cells along the axis.
        const int i0 = axis == 0 ? b.xs - 1 : b.xs, j0 = axis == 0 ? b.ys : b.ys - 1;
        for (int j = j0; j < b.ye(); ++j)
          for (int i = i0; i < b.xe(); ++i) {
            soil_through[j][i] += through[j][i];
            if (soil_mass_through && through[j][i] != 0.0) soil_mass_through[j][i] += through[j][i] * (*face_density)[j][i];
          }
      }
    }
    if (axis == 1 || grid_.bounded(Side::west))  // no soil leaves through a periodic side
      outflow_ += interface::boundary_outflow(axis, dt, c.data(), face_velocity, grid_.dx_data(), grid_.dy_data(), b,
                                              domain_cells(), radial);
    else if (b.xe() == grid_.nx()) {  // the rank that holds the last column, east of which is the join
      std::deque<ConstFieldArray> m;  // the shares the sweep starts from, with the first column's as ghosts
      if (densities_differ())
        for (const auto& f : from_shares ? share_ : share_tmp_) m.emplace_back(grid_.field_dm(), f->local());
      const int i = grid_.nx() - 1;
      const double length = grid_.spec().upper[0] - grid_.spec().lower[0];
      for (int j = b.ys; j < b.ye(); ++j) {
        const double moved = interface::face_soil_volume_x(i, j, dt, c.data(), face_velocity, grid_.dx_data(),
                                                           grid_.dy_data(), domain_cells());
        if (moved != 0.0)  // the donor's soil: cell i + 1 is the first column's ghost
          join_moment_ += (cell_soil_density(m, moved > 0.0 ? i : i + 1, j) - settings_.air_density) * length * moved;
      }
    }
  }
  fill_fraction_ghosts(to);
  if (materials_)
    for (auto& f : from_shares ? share_tmp_ : share_) fill_share_ghosts(*f);
}

void SoilPhase::transport_displacement(const FlowSolver& flow, double dt) {
  if (!settings_.displacement) return;
  const auto& b = grid_.owned();
  ConstFieldArray c(grid_.field_dm(), c_->local());
  ConstFieldArray fx = local_read(grid_, flow.face_velocity(0)), fy = local_read(grid_, flow.face_velocity(1));
  ConstFieldArray u = local_read(grid_, flow.velocity(0)), v = local_read(grid_, flow.velocity(1));
  const double* const* vel[2] = {u.data(), v.data()};
  // Soil flux (c v . n A)_f of a face of (i, j) ([VoF] Eq. 20), outward.
  auto soil_flux = [&](int i, int j, double face_vel, int in, int jn, double area, double sign) {
    const bool outside = grid_.outside(in, jn);
    const double cf = outside ? c[j][i] : 0.5 * (c[j][i] + c[jn][in]);
    return sign * face_vel * area * cf;
  };
  // Face areas carry the radius in axisymmetric geometry; with no swirl the r-component of
  // div(c v u) has no extra hoop term, so the planar form holds component by component.
  auto faces = [&](int i, int j, auto&& visit) {
    visit(soil_flux(i, j, fx[j][i], i + 1, j, grid_.face_area(0, i, j, 1.0), 1.0), i + 1, j);
    visit(soil_flux(i, j, fx[j][i - 1], i - 1, j, grid_.face_area(0, i, j, -1.0), -1.0), i - 1, j);
    visit(soil_flux(i, j, fy[j][i], i, j + 1, grid_.face_area(1, i, j, 1.0), 1.0), i, j + 1);
    visit(soil_flux(i, j, fy[j - 1][i], i, j - 1, grid_.face_area(1, i, j, -1.0), -1.0), i, j - 1);
  };
  // The donor-cell update is stable while no cell sends out more than it holds in one sweep: the
  // flow step may be longer (time.courant > 1, several VoF sweeps), so the step is split as needed.
  double most_out = 0.0;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      double out = 0.0;  // a blocked cell's faces are walls, of no flux
      faces(i, j, [&](double flux, int, int) { out += std::max(flux, 0.0); });
      most_out = std::max(most_out, out * dt / grid_.volume(i, j));
    }
  // A flow that runs away (the step's divergence check comes after) gets no more than a bounded count.
  constexpr double most_sweeps = 1000.0;
  const int sweeps = int(std::clamp(std::ceil(mpi_max(grid_.comm(), most_out) - 1e-12), 1.0, most_sweeps));
  const double h = dt / sweeps;
  const BlockedView mask(grid_, blocked_);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (int a = 0; a < 2; ++a) {
      ConstFieldArray d(grid_.field_dm(), disp_[a]->local());
      FieldArray dn(grid_.field_dm(), disp_new_[a]->global());
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          if (is_blocked(mask.data(), i, j)) {  // its local values mirror the soil's
            dn[j][i] = 0.0;
            continue;
          }
          double out = 0.0;  // donor-cell displacement
          faces(i, j, [&](double flux, int in, int jn) { out += flux * (flux >= 0.0 ? d[j][i] : d[jn][in]); });
          dn[j][i] = d[j][i] + h * (c[j][i] * vel[a][j][i] - out / grid_.volume(i, j));
        }
    }
    for (int a = 0; a < 2; ++a) VecCopy(disp_new_[a]->global(), disp_[a]->global());
    // Every change of the displacement ends with its ghosts filled, as c's does: the next sweep reads
    // them, and a step's snapshot and a checkpoint copy the local vectors.
    fill_displacement_ghosts();
  }
}

}  // namespace granflow

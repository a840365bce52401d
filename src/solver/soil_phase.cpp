#include "solver/soil_phase.hpp"

#include "io/checkpoint.hpp"
#include "io/collective_failure.hpp"
#include "mesh/copied_ghosts.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/gather.hpp"
#include "mesh/obstacles.hpp"
#include "mesh/side_ghosts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>
#include <stdexcept>

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
    for (int a = 0; a < grid.dimension(); ++a) {
      face_soil_[a] = make();
      face_soil_[a]->set(0.0);
    }
    if (settings.materials_differ_in_density()) {
      soil_densities_.push_back(settings.soil_density);
      for (const auto& m : settings.materials) soil_densities_.push_back(m.rheology.density);
      lightest_soil_ = *std::min_element(soil_densities_.begin(), soil_densities_.end());
      heaviest_soil_ = *std::max_element(soil_densities_.begin(), soil_densities_.end());
      for (int a = 0; a < grid.dimension(); ++a) {
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
  relative_stress_ = make();
  dissipation_ = make();
  for (int a = 0; a < grid.dimension(); ++a) {
    disp_[a] = make();
    disp_new_[a] = make();
    disp_[a]->set(0.0);
  }
  for (Field* f : {c_.get(), c_tmp_.get(), dilatation_.get(), region_[0].get(), region_[1].get(), strain_norm_.get(), rate_norm_.get(), lode_.get(), stress_ratio_.get(), relative_stress_.get(), dissipation_.get(),
                   overburden_.get()})
    f->set(0.0);
}

std::vector<Field*> SoilPhase::state_fields() {
  std::vector<Field*> fields{c_.get(), disp_[0].get(), disp_[1].get()};
  if (disp_[2]) fields.push_back(disp_[2].get());
  for (auto& f : share_) fields.push_back(f.get());
  return fields;
}

std::string SoilPhase::checkpoint_field_names() const {
  std::string names = disp_[2] ? "c displacement_x displacement_y displacement_z" : "c displacement_x displacement_y";
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
  const ConstFieldArray c_array(grid_.field_dm(), c_->global());
  const VolumeView c = c_array.volume();
  const auto& b = grid_.owned();
  const bool layers = grid_.dimension() == 3;
  for (int k = b.zs; k < b.ze() && problem.empty(); ++k)
    for (int j = b.ys; j < b.ye() && problem.empty(); ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        if (!(c[k][j][i] >= -margin && c[k][j][i] <= 1 + margin)) {
          const std::string cell = layers ? fmt::format("({}, {}, {})", i, j, k) : fmt::format("({}, {})", i, j);
          problem = fmt::format("the checkpoint is damaged: its soil fraction c is {} in cell {}, outside [0, 1]",
                                c[k][j][i], cell);
          break;
        }
  if (auto text = first_failure(grid_.comm(), problem); !text.empty()) throw CheckpointError(text);
}

void SoilPhase::clear_blocked_cells() {
  // A checkpoint's ghosts beyond an inlet are those of the run that wrote it, whose inlet the case may
  // have changed.
  const bool inlet = has_inlet(flow_settings_.boundaries);
  if (!blocked_ && !inlet) return;
  for (auto& f : disp_)
    if (f) zero_blocked_cells(grid_, blocked_, *f);
  fill_fraction_ghosts(*c_);  // zeroes c there, and mirrors anew
  fill_share_ghosts(share_);
  if (inlet) fill_displacement_ghosts();
}

void SoilPhase::restore_state() {
  saved_.restore(state_fields());
  clear_blocked_cells();
  sweep_parity_ = saved_parity_;
  outflow_ = saved_outflow_;
  join_moment_ = saved_join_moment_;
}

void SoilPhase::initialise() {
  if (grid_.dimension() == 3) return initialise_3d();
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
  clear_round_off_soil();
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
  fill_share_ghosts(share_);
}

// Ghosts of a material share: walls copy the nearest cell (zero gradient), blocked cells hold none;
// soil coming in through an atmosphere side is the rheology's own (share 0), through an inlet the
// inlet's material (share 1 of its own material, 0 of the others) where it is open.
void SoilPhase::fill_share_ghosts(Field& f, int material) const {
  zero_blocked_cells(grid_, blocked_, f);
  f.scatter_to_local();
  FieldArray a(grid_.field_dm(), f.local());
  mirror_into_blocked(grid_, blocked_, a.volume(), 1.0);
  fill_side_ghosts(grid_, a.volume(), [&](Side side, double, double first, const int* at) {
    const auto& bc = boundary(flow_settings_.boundaries, side);
    if (bc.kind == BoundaryKind::atmosphere) return 0.0;
    if (lets_in(bc, grid_, side, at[0], at[1], at[2])) return bc.inflow_material == material ? 1.0 : 0.0;
    return first;
  });
}


std::deque<ConstFieldArray> SoilPhase::share_arrays(bool ghosted) const {
  std::deque<ConstFieldArray> arrays;
  for (const auto& f : share_) arrays.emplace_back(grid_.field_dm(), ghosted ? f->local() : f->global());
  return arrays;
}

void SoilPhase::cell_shares(const std::deque<ConstFieldArray>& m, int i, int j, int k, Shares& out) const {
  for (size_t n = 0; n < m.size(); ++n) out[n] = m[n].volume()[k][j][i];
}

// Ghosts of c: soil carried in through an atmosphere boundary has the boundary's inflow fraction,
// through an inlet the inlet's below its soil depth (each ghost the share of its height below it);
// walls mirror, which gives interface normals meeting a wall at right angles, and so does an inlet
// outside its opening.
void SoilPhase::fill_fraction_ghosts(Field& f) const {
  zero_blocked_cells(grid_, blocked_, f);  // no soil in a blocked cell (a sweep leaves there the mirror it read)
  f.scatter_to_local();
  FieldArray a(grid_.field_dm(), f.local());
  mirror_into_blocked(grid_, blocked_, a.volume(), 1.0);  // an obstacle's walls mirror, as the domain's
  const double bottom = grid_.spec().lower[1];
  fill_side_ghosts(grid_, a.volume(), [&](Side side, double inner, double, const int* where) {
    const auto& bc = boundary(flow_settings_.boundaries, side);
    if (lets_in(bc, grid_, side, where[0], where[1], where[2])) {
      const int j = where[1];
      return inlet_face_soil_fraction(bc, grid_.yf(j) - grid_.dy(j), grid_.yf(j), bottom);
    }
    return bc.kind == BoundaryKind::atmosphere ? bc.inflow_soil_fraction : inner;
  });
}

// Ghosts of the displacement: zero gradient, but soil entering through an inlet has not moved yet.
void SoilPhase::fill_displacement_ghosts() {
  for (auto& d : disp_)
    if (d) {
      fill_copied_ghosts(grid_, blocked_, *d);
      if (!has_inlet(flow_settings_.boundaries)) continue;
      FieldArray a = local_array(grid_, *d);
      fill_side_ghosts(grid_, a.volume(), [&](Side side, double, double first, const int* at) {
        return lets_in(boundary(flow_settings_.boundaries, side), grid_, side, at[0], at[1], at[2]) ? 0.0 : first;
      });
    }
}

}  // namespace granflow

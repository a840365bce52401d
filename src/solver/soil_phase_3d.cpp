// The soil phase on a mesh of layers (3D): what soil_phase.cpp, soil_properties.cpp, soil_advection.cpp
// and soil_diagnostics.cpp do on a planar mesh. The same equations and the same choices as in 2D, each
// noted where it differs: the soil fraction and the materials' shares are carried by three sweeps
// (vof_advection_3d.hpp, material_sweep_3d), the strain rate and the Euler-Almansi strain are the full
// 3D tensors (docs/method.md, "In three dimensions"). The displacement's transport serves both
// (soil_advection.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/axis_views.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "models/interface/initial_shapes_3d.hpp"
#include "models/interface/material_transport.hpp"
#include "models/interface/vof_advection_3d.hpp"
#include "models/interface/wetted_fraction.hpp"
#include "models/mixture/potential_energy.hpp"
#include "models/rheology/invariants.hpp"
#include "models/strain/euler_almansi.hpp"
#include "operators/face_interpolation.hpp"
#include "operators/strain_rate.hpp"
#include "solver/cell_faces.hpp"
#include "solver/divergence_error.hpp"
#include "solver/soil_phase.hpp"

namespace granflow {

namespace {

interface::CellWidths3 widths_of(const Grid& g) { return {g.dx_data(), g.dy_data(), g.dz_data()}; }

VelocityArrays3 velocity_arrays(const AxisViews& v) { return {v.view[0], v.view[1], v.view[2]}; }

}  // namespace

void SoilPhase::initialise_3d() {
  // The 3D shapes, and the 2D ones extruded across the whole depth (a planar case's block across a
  // channel).
  const interface::ShapeUnion3 soil(settings_.initial_solids(grid_.spec().lower[2], grid_.spec().upper[2]));
  {
    FieldArray c(grid_.field_dm(), c_->global());
    const auto& b = grid_.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const interface::Point3 lower{grid_.xc(i) - 0.5 * grid_.dx(i), grid_.yc(j) - 0.5 * grid_.dy(j),
                                        grid_.zc(k) - 0.5 * grid_.dz(k)};
          c.volume()[k][j][i] =
              soil.fraction(lower, {lower[0] + grid_.dx(i), lower[1] + grid_.dy(j), lower[2] + grid_.dz(k)});
        }
  }
  clear_round_off_soil();
  if (materials_) initialise_materials_3d();
}

// Each material's share of a cell's soil, as in 2D (SoilPhase::initialise_materials): by 16 x 16 x 16
// midpoint samples, a sample in the shapes' union belonging to the last shape listed that holds it;
// a cell that one shape alone reaches is all of that shape's material.
void SoilPhase::initialise_materials_3d() {
  constexpr int samples = 16;
  const auto& spec = grid_.spec();
  const auto solids = settings_.initial_solids(spec.lower[2], spec.upper[2]);
  std::vector<std::array<interface::Point3, 2>> boxes;
  for (const auto& solid : solids) boxes.push_back(interface::bounding_box(solid));
  const interface::ShapeUnion3 shapes(solids);
  const auto& material_of = settings_.initial_material;  // per shape as listed, as the solids are
  if (material_of.size() != shapes.size() || settings_.initial_shape_is_solid.size() != shapes.size())
    throw std::invalid_argument("SoilPhase: soil materials need each initial shape's material and kind, in the order "
                                "listed (as the case file gives them)");
  const auto& b = grid_.owned();
  const ConstFieldArray c(grid_.field_dm(), c_->global());
  std::deque<FieldArray> m;
  for (auto& f : share_) m.emplace_back(grid_.field_dm(), f->global());
  const int count = int(share_.size()), shape_count = int(shapes.size());
  std::vector<double> weight(size_t(count) + 1);
  std::vector<int> reaching;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        for (int n = 0; n < count; ++n) m[size_t(n)].volume()[k][j][i] = 0.0;
        if (!(c.volume()[k][j][i] > 0.0)) continue;
        const interface::Point3 lower{grid_.xc(i) - 0.5 * grid_.dx(i), grid_.yc(j) - 0.5 * grid_.dy(j),
                                      grid_.zc(k) - 0.5 * grid_.dz(k)};
        const interface::Point3 upper{lower[0] + grid_.dx(i), lower[1] + grid_.dy(j), lower[2] + grid_.dz(k)};
        reaching.clear();
        for (int shape = 0; shape < shape_count; ++shape) {
          bool overlaps = true;
          for (int a = 0; a < 3; ++a)
            overlaps = overlaps && boxes[size_t(shape)][0][a] < upper[a] && boxes[size_t(shape)][1][a] > lower[a];
          if (overlaps) reaching.push_back(shape);
        }
        if (reaching.empty()) continue;  // soil no shape holds: none (round-off)
        std::fill(weight.begin(), weight.end(), 0.0);
        if (reaching.size() > 1)
          for (int sz = 0; sz < samples; ++sz)
            for (int sy = 0; sy < samples; ++sy)
              for (int sx = 0; sx < samples; ++sx) {
                const double x = lower[0] + (sx + 0.5) * grid_.dx(i) / samples,
                             y = lower[1] + (sy + 0.5) * grid_.dy(j) / samples,
                             z = lower[2] + (sz + 0.5) * grid_.dz(k) / samples;
                for (auto shape = reaching.rbegin(); shape != reaching.rend(); ++shape)
                  if (shapes.shape_contains(size_t(*shape), x, y, z)) {
                    weight[size_t(material_of[size_t(*shape)])] += 1.0;
                    break;
                  }
              }
        double total = 0.0;
        for (double w : weight) total += w;
        if (total > 0.0)
          for (int n = 0; n < count; ++n) m[size_t(n)].volume()[k][j][i] = weight[size_t(n) + 1] / total;
        // One shape, or a sliver the samples missed: the last shape whose bounding box reaches the cell.
        else if (const int n = material_of[size_t(reaching.back())]; n > 0)
          m[size_t(n - 1)].volume()[k][j][i] = 1.0;
      }
  m.clear();
  fill_share_ghosts(share_);
}

void SoilPhase::update_properties_3d(FlowSolver& flow) const {
  const auto& b = grid_.owned();
  const ConstFieldArray c(grid_.field_dm(), c_->global()), p(grid_.field_dm(), flow.pressure().global());
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  FieldArray rho(grid_.field_dm(), flow.density().global()), mu(grid_.field_dm(), flow.viscosity().global());
  const auto overburden = overburden_if_floor();
  const auto m = share_arrays(false);
  Shares shares{};
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        const double cc = c.volume()[k][j][i];
        if (materials_) cell_shares(m, i, j, k, shares);
        rho.volume()[k][j][i] = densities_differ() ? mixture_density(cc, soil_density(shares)) : mixture_density(cc);
        const double pressure =
            overburden ? std::max(p.volume()[k][j][i], ambient_pressure_ + overburden->volume()[k][j][i]) : p.volume()[k][j][i];
        mu.volume()[k][j][i] = mixture_viscosity(cc, pressure, cell_strain_rate(grid_, velocity_arrays(vel), i, j, k),
                                                 materials_ ? shares.data() : nullptr);
      }
}

// As update_face_viscosity in 2D (soil_properties.cpp).
void SoilPhase::update_face_viscosity_3d(FlowSolver& flow) const {
  const auto kind = flow_settings_.numerics.face_viscosity;
  const auto& g = flow_settings_.gravity;
  const bool at_face = settings_.strain_rate == StrainRateAt::face;
  const bool face_fraction = settings_.face_fraction == FaceFraction::face;
  const bool quadratic_wall = flow_settings_.numerics.quadratic_wall_gradient;
  const ConstFieldArray c_array = local_read(grid_, *c_), p_array = local_read(grid_, flow.pressure()),
                        rho_array = local_read(grid_, flow.density());
  const VolumeView c = c_array.volume(), p = p_array.volume(), rho = rho_array.volume();
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  const VelocityArrays3 v = velocity_arrays(vel);
  std::optional<ConstFieldArray> obstacle_of;  // which obstacle a blocked cell belongs to
  if (obstacle_index_) obstacle_of.emplace(grid_.field_dm(), obstacle_index_->local());
  // With soil materials: the shares of a cell (own, other), null without.
  const auto m = share_arrays(true);
  Shares own{}, other{};
  const double* own_shares = materials_ ? own.data() : nullptr;
  const double* other_shares = materials_ ? other.data() : nullptr;
  // Face (axis, i, j, k) lies between cell (i, j, k) and its neighbour at +1 along axis.
  auto face = [&](int axis, int i, int j, int k, double pressure) {
    const int in = i + (axis == 0), jn = j + (axis == 1), kn = k + (axis == 2);
    const double c_low = c[k][j][i], c_high = c[kn][jn][in];
    if (c_low == 0.0 && c_high == 0.0) {  // air on both sides: its viscosity, which reads no strain rate
      const double air = mixture_viscosity(0.0, pressure, rheology::StrainRate{});
      return at_face ? air : face_mean(kind, air, air);
    }
    if (materials_) {
      cell_shares(m, i, j, k, own);
      cell_shares(m, in, jn, kn, other);
    }
    if (at_face) {
      const auto rate = face_strain_rate(grid_, v, axis, i, j, k);
      // One evaluation at the face's soil fraction; also where both sides hold the same mixture (the bulk).
      if (face_fraction || c_high == c_low)
        return face_mixture_viscosity(c_low, c_high, 0.5 * (c_low + c_high), pressure, rate, own, other);
      return face_mean(kind, mixture_viscosity(c_low, pressure, rate, own_shares),
                       mixture_viscosity(c_high, pressure, rate, other_shares));
    }
    return face_mean(kind, mixture_viscosity(c_low, pressure, cell_strain_rate(grid_, v, i, j, k), own_shares),
                     mixture_viscosity(c_high, pressure, cell_strain_rate(grid_, v, in, jn, kn), other_shares));
  };
  fill_owned_faces_3d(
      grid_, {&flow.face_viscosity(0), &flow.face_viscosity(1), &flow.face_viscosity(2)},
      [&](int axis, int i, int j, int k) {
        const int in = i + (axis == 0), jn = j + (axis == 1), kn = k + (axis == 2);
        return face(axis, i, j, k, 0.5 * (p[k][j][i] + p[kn][jn][in]));
      },
      [&](int axis, int i, int j, int k, int sign) {  // the cell's pressure carried hydrostatically to the wall
        const double half = 0.5 * sign * grid_.width(axis, index_along(axis, i, j, k));
        const double pressure = p[k][j][i] + rho[k][j][i] * g[axis] * half;
        // The wall: a side of the domain, or an obstacle's face (of its own friction, or none).
        const int in = i + (axis == 0 ? sign : 0), jn = j + (axis == 1 ? sign : 0), kn = k + (axis == 2 ? sign : 0);
        const bool obstacle = !grid_.outside(in, jn, kn);
        if (materials_) cell_shares(m, i, j, k, own);
        const int obstacle_index = obstacle && obstacle_of ? int(obstacle_of->volume()[kn][jn][in]) : 0;
        const auto& bc = !obstacle            ? boundary(flow_settings_.boundaries, side_of(axis, sign))
                         : obstacle_index > 0 ? obstacle_walls_[size_t(obstacle_index - 1)]
                                              : obstacle_wall;
        // The face between the ghost and the cell, the ghost's velocity encoding the wall; with the
        // quadratic wall gradient, its rate across the wall as the momentum flux takes it.
        const int il = i - (sign < 0 && axis == 0), jl = j - (sign < 0 && axis == 1), kl = k - (sign < 0 && axis == 2);
        auto wall_rate = [&] {
          return quadratic_wall && bc.kind != BoundaryKind::atmosphere
                     ? quadratic_wall_strain_rate(grid_, v, axis, i, j, k, sign,
                                                  held_velocity(bc, grid_, side_of(axis, sign), i, j, k),
                                                  bc.kind == BoundaryKind::slip)
                     : face_strain_rate(grid_, v, axis, il, jl, kl);
        };
        if (!at_face) {
          const auto cell_rate = cell_strain_rate(grid_, v, i, j, k);
          if (!bc.friction) return mixture_viscosity(c[k][j][i], pressure, cell_rate, own_shares);
          return wall_mixture_viscosity(c[k][j][i], pressure, cell_rate, own_shares, bc, wall_rate(), axis);
        }
        // The face's own soil fraction: how much of it the cell's soil covers (a film on the floor
        // covers all of the floor under it).
        const double cf = face_fraction ? interface::wetted_side_fraction(c, grid_.dx_data(), grid_.dy_data(),
                                                                          grid_.dz_data(), i, j, k, axis, sign)
                                        : c[k][j][i];
        const auto rate = wall_rate();
        return wall_mixture_viscosity(cf, pressure, rate, own_shares, bc, rate, axis);
      },
      BlockedView(grid_, blocked_).data());  // an obstacle's wall as a wall side: its velocity mirrored behind it
}

double SoilPhase::interface_courant_3d(const FlowSolver& flow, double dt) const {
  const AxisViews face(grid_, [&](int a) -> const Field& { return flow.face_velocity(a); });
  double co = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    co = larger_or_nan(co, interface::max_sweep_courant(axis, dt, face.view[axis], widths_of(grid_), grid_.owned()));
  return mpi_max(grid_.comm(), co);
}

// The three sweeps of vof_advection_3d.hpp, in as many sub-steps as the sweep's Courant limit needs,
// taken over the whole mesh (in 2D only near the soil, SoilPhase::interface_courant); with materials,
// each sweep of c followed by the same sweep of their shares (material_sweep_3d).
void SoilPhase::advect_3d(FlowSolver& flow, double dt) {
  const double co = interface_courant_3d(flow, dt);
  constexpr double max_substeps = 1000, allowance = 1e-9;
  if (!(co / settings_.interface_courant <= max_substeps))
    throw DivergenceError(fmt::format("the soil fraction would need {:.3g} sweeps in a step of {:.3g} s: the flow "
                                      "has diverged (lower time.dt, or let time.adaptive size the step)",
                                      co / settings_.interface_courant, dt));
  const int substeps = std::max(1, int(std::ceil(co / settings_.interface_courant - allowance)));
  const double h = dt / substeps;
  const auto& b = grid_.owned();
  const AxisViews face(grid_, [&](int a) -> const Field& { return flow.face_velocity(a); });
  const interface::DomainCells3 domain{grid_.nx(), grid_.ny(), grid_.nz(), grid_.periodic_x()};
  // Under the conservative momentum transport the soil volume per unit area through each face adds up
  // in the flow's mass fluxes, which become mass fluxes below, as in 2D (soil_advection.cpp); with soils
  // of several densities their mass too.
  const bool carry_mass = flow.carries_mass_transport();
  std::optional<FieldArray> soil_through[3], soil_mass_through[3];
  if (carry_mass) {
    {
      const ConstFieldArray c(grid_.field_dm(), c_->global());
      FieldArray rho0 = local_array(grid_, flow.start_density());
      const auto m = share_arrays(false);
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i) {
            const double cc = c.volume()[k][j][i];
            rho0.volume()[k][j][i] =
                densities_differ() ? mixture_density(cc, cell_soil_density(m, i, j, k)) : mixture_density(cc);
          }
    }
    for (int a = 0; a < 3; ++a) {
      flow.mass_flux(a).set(0.0);
      soil_through[a].emplace(grid_.field_dm(), flow.mass_flux(a).local());
      if (densities_differ()) {
        soil_mass_through_[a]->set(0.0);
        soil_mass_through[a].emplace(grid_.field_dm(), soil_mass_through_[a]->local());
      }
    }
  }
  const int start[3] = {b.xs, b.ys, b.zs}, end[3] = {b.xe(), b.ye(), b.ze()};
  // Calls at(i, j, k) on the faces bounding the owned cells along the axis, the block's low side's too.
  auto for_faces = [&](int axis, auto&& at) {
    int lo[3] = {start[0], start[1], start[2]};
    --lo[axis];
    for (int k = lo[2]; k < end[2]; ++k)
      for (int j = lo[1]; j < end[1]; ++j)
        for (int i = lo[0]; i < end[0]; ++i) at(i, j, k);
  };
  for (int s = 0; s < substeps; ++s) {
    {
      const ConstFieldArray c(grid_.field_dm(), c_->local());
      FieldArray cc(grid_.field_dm(), dilatation_->local());
      interface::dilatation_indicator(c.volume(), b, cc.volume());
    }
    // The materials' shares at the start, held with the indicator over the three sweeps.
    for (size_t n = 0; n < share_.size(); ++n)
      PetscCallAbort(grid_.comm(), VecCopy(share_[n]->global(), share_start_[n]->global()));
    // x y z, then z y x in the next sub-step (Strang's alternation, as x y then y x in 2D): a flow that
    // does not vary along z is swept as the planar one is.
    const bool forward = sweep_parity_ == 0;
    sweep_parity_ = 1 - sweep_parity_;
    Field* from = c_.get();
    Field* to = c_tmp_.get();
    auto* shares_from = &share_;
    auto* shares_to = &share_tmp_;
    for (int n = 0; n < 3; ++n) {
      const int axis = forward ? n : 2 - n;
      {
        const ConstFieldArray c(grid_.field_dm(), from->local()), cc(grid_.field_dm(), dilatation_->local());
        FieldArray c_new(grid_.field_dm(), to->global());
        if (!materials_) {
          interface::vof_sweep(axis, h, c.volume(), face.view[axis], cc.volume(), widths_of(grid_), b, c_new.volume(),
                               domain, carry_mass ? soil_through[axis]->volume() : nullptr);
        } else {
          // The sweep's own face fluxes, which carry the materials' shares, then add up in soil_through.
          FieldArray through(grid_.field_dm(), face_soil_[axis]->local());
          for_faces(axis, [&](int i, int j, int k) { through.volume()[k][j][i] = 0.0; });
          interface::vof_sweep(axis, h, c.volume(), face.view[axis], cc.volume(), widths_of(grid_), b, c_new.volume(),
                               domain, through.volume());
          std::deque<ConstFieldArray> m, m0;
          std::deque<FieldArray> m_new;
          std::vector<const double* const* const*> m_of, m0_of;
          std::vector<double***> m_new_of;
          for (size_t q = 0; q < share_.size(); ++q) {
            m_of.push_back(m.emplace_back(grid_.field_dm(), (*shares_from)[q]->local()).volume());
            m0_of.push_back(m0.emplace_back(grid_.field_dm(), share_start_[q]->global()).volume());
            m_new_of.push_back(m_new.emplace_back(grid_.field_dm(), (*shares_to)[q]->global()).volume());
          }
          std::optional<FieldArray> face_density;
          if (soil_mass_through[axis]) face_density.emplace(grid_.field_dm(), face_soil_density_[axis]->local());
          interface::material_sweep_3d(axis, h, c.volume(), c_new.volume(), int(share_.size()), m_of.data(),
                                       m0_of.data(), face.view[axis], through.volume(), cc.volume(), widths_of(grid_), b,
                                       m_new_of.data(), soil_densities_.data(),
                                       face_density ? face_density->volume() : nullptr);
          if (carry_mass)
            for_faces(axis, [&](int i, int j, int k) {
              const double f = through.volume()[k][j][i];
              soil_through[axis]->volume()[k][j][i] += f;
              if (face_density && f != 0.0) soil_mass_through[axis]->volume()[k][j][i] += f * face_density->volume()[k][j][i];
            });
        }
        outflow_ += interface::boundary_outflow(axis, h, c.volume(), face.view[axis], widths_of(grid_), b, domain);
        if (axis == 0 && grid_.periodic_x() && b.xe() == grid_.nx()) {
          // The soil through the join east of the last column runs on in the budget's first moment
          // (join_moment_, soil_diagnostics.cpp): the donor's excess over the air's density times the
          // strip's length. The donor's shares are those the sweep started from (cell i + 1: the first
          // column's ghost).
          std::deque<ConstFieldArray> m;
          if (densities_differ())
            for (const auto& f : *shares_from) m.emplace_back(grid_.field_dm(), f->local());
          const int i = grid_.nx() - 1;
          const double length = grid_.spec().upper[0] - grid_.spec().lower[0];
          for (int k = b.zs; k < b.ze(); ++k)
            for (int j = b.ys; j < b.ye(); ++j) {
              const double moved =
                  interface::face_soil_volume_x(i, j, k, h, c.volume(), face.view[0], widths_of(grid_), domain);
              if (moved != 0.0)
                join_moment_ +=
                    (cell_soil_density(m, moved > 0.0 ? i : i + 1, j, k) - settings_.air_density) * length * moved;
            }
        }
      }
      fill_fraction_ghosts(*to);
      fill_share_ghosts(*shares_to);
      std::swap(from, to);
      std::swap(shares_from, shares_to);
    }
    // Three sweeps end in c_tmp_ (and share_tmp_): back to c_.
    c_->copy_from(*from);
    for (size_t q = 0; q < share_.size(); ++q) share_[q]->copy_from(*(*shares_from)[q]);
  }
  clear_round_off_soil();
  if (!carry_mass) return;
  // The soil volume (and mass) through each face over the step to the mixture's mass flux, as in 2D.
  for (int axis = 0; axis < 3; ++axis) {
    double*** m = soil_through[axis]->volume();
    const VolumeView u = face.view[axis];
    for_faces(axis, [&](int i, int j, int k) {
      const double soil_mass = densities_differ() ? soil_mass_through[axis]->volume()[k][j][i] : 0.0;
      m[k][j][i] = face_mass_flux(u[k][j][i], m[k][j][i], soil_mass, dt);
    });
  }
  for (auto& through : soil_through) through.reset();  // the mass fluxes are the flow's to read now
  flow.carry_momentum_mass(dt);
}

// ||D|| ([YS] Eq. 8), the Lode angle, the strain norm ([VoF] Eqs. 13-14) and the stress ratios.
void SoilPhase::compute_diagnostics_3d(const FlowSolver& flow) {
  const auto& b = grid_.owned();
  const AxisViews disp(grid_, disp_);
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  const ConstFieldArray p(grid_.field_dm(), flow.pressure().global());
  const auto overburden = overburden_if_floor();
  FieldArray en(grid_.field_dm(), strain_norm_->global()), rn(grid_.field_dm(), rate_norm_->global()),
      lo(grid_.field_dm(), lode_->global()), ratio(grid_.field_dm(), stress_ratio_->global()),
      relative(grid_.field_dm(), relative_stress_->global());
  const BlockedView mask(grid_, blocked_);
  const auto m = share_arrays(false);
  Shares shares{};
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j, k)) {  // no soil, no flow
          en.volume()[k][j][i] = rn.volume()[k][j][i] = lo.volume()[k][j][i] = relative.volume()[k][j][i] = 0.0;
          ratio.volume()[k][j][i] = 1.0;
          continue;
        }
        // grad u by central differences: g[a][d] = d u_a / d x_d.
        strain::DisplacementGradient3 g{};
        for (int d = 0; d < 3; ++d) {
          const int di = d == 0, dj = d == 1, dk = d == 2;
          const int along = index_along(d, i, j, k);
          const double span = grid_.centre(d, along + 1) - grid_.centre(d, along - 1);
          for (int a = 0; a < 3; ++a)
            g.g[a][d] = (disp.view[a][k + dk][j + dj][i + di] - disp.view[a][k - dk][j - dj][i - di]) / span;
        }
        strain::AlmansiStrain3 e;
        strain::almansi_strain(g, e);
        en.volume()[k][j][i] = strain::deviatoric_norm(e);
        const auto D = cell_strain_rate(grid_, velocity_arrays(vel), i, j, k);
        rn.volume()[k][j][i] = rheology::norm(rheology::deviatoric(D));
        lo.volume()[k][j][i] = rheology::lode_angle(D) * 180.0 / std::numbers::pi;
        const double cell_p = p.volume()[k][j][i];
        const double pressure =
            (overburden ? std::max(cell_p, ambient_pressure_ + overburden->volume()[k][j][i]) : cell_p) - ambient_pressure_;
        if (materials_) {
          cell_shares(m, i, j, k, shares);
          ratio.volume()[k][j][i] = materials_->stress_ratio_to_drucker_prager(D, pressure, shares.data());
          relative.volume()[k][j][i] = materials_->relative_shear_stress(D, pressure, shares.data());
        } else {
          ratio.volume()[k][j][i] = rheology_ ? rheology_->stress_ratio_to_drucker_prager(D, pressure) : 1.0;
          relative.volume()[k][j][i] = rheology_ ? rheology_->relative_shear_stress(D, pressure) : 1.0;
        }
      }
}

// The viscous dissipation, face by face as in 2D (soil_diagnostics.cpp): an interior face's work
// mu_f A d [f_n (dv_n/dn)^2 + sum over tangential c of (dv_c/dn)(dv_c/dn + x dv_n/dx_c)], half to
// either cell; a wall face's from the two-point wall gradient, all to its cell (an obstacle's wall,
// static and no-slip, all to the open cell). Fills dissipation_ and the Lode-binned rates; returns the
// rank's sum.
double SoilPhase::compute_dissipation_3d(const FlowSolver& flow) {
  const auto& b = grid_.owned();
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  const AxisViews face_mu(grid_, [&](int a) -> const Field& { return flow.face_viscosity(a); });
  const auto& num = flow_settings_.numerics;
  const double normal_factor = num.transpose_stress ? 2.0 : 1.0, cross = num.transpose_stress ? 1.0 : 0.0;
  FieldArray out_array(grid_.field_dm(), dissipation_->global());
  double*** out = out_array.volume();
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) out[k][j][i] = 0.0;
  auto owned = [&](int i, int j, int k) {
    return i >= b.xs && i < b.xe() && j >= b.ys && j < b.ye() && k >= b.zs && k < b.ze();
  };
  const BlockedView mask(grid_, blocked_);
  auto blocked = [&](int i, int j, int k) { return is_blocked(mask.data(), i, j, k); };
  // The face fg of cell (i, j, k): its work rate.
  auto face_work = [&](int i, int j, int k, const FaceGeometry& fg) {
    const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
    const double mu_f = on_face(face_mu.view, i, j, k, fg);
    const double A = grid_.face_area(fg.axis, i, j, k, fg.sign);
    if (grid_.outside(in, jn, kn) || blocked(in, jn, kn)) {
      const auto& bc = blocked(in, jn, kn) ? obstacle_wall : boundary(flow_settings_.boundaries, fg.side);
      if (bc.kind == BoundaryKind::atmosphere) return 0.0;
      const auto held = held_velocity(bc, grid_, fg.side, i, j, k);
      double work = 0.0;
      for (int c = 0; c < 3; ++c) {
        if (bc.kind == BoundaryKind::slip && c != fg.axis) continue;  // no shear on a slip side
        const double wall = held[c];  // a wall's normal component is zero
        const double gradient = wall_gradient(grid_, vel.view[c], i, j, k, fg, wall, num.quadratic_wall_gradient);
        work += (c == fg.axis ? normal_factor : 1.0) * mu_f * A * gradient * (vel.view[c][k][j][i] - wall);
      }
      return work;
    }
    const double d = std::abs(grid_.centre(fg.axis, index_along(fg.axis, in, jn, kn)) -
                              grid_.centre(fg.axis, index_along(fg.axis, i, j, k)));
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double across = (vel.view[c][kn][jn][in] - vel.view[c][k][j][i]) / d;
      if (c == fg.axis) {
        sum += normal_factor * across * across;
        continue;
      }
      // d v_n / d x_c: the mean of the two cells' central differences.
      const int ci = c == 0, cj = c == 1, ck = c == 2;
      const double span = grid_.centre(c, index_along(c, i, j, k) + 1) - grid_.centre(c, index_along(c, i, j, k) - 1);
      const VolumeView qn = vel.view[fg.axis];
      const double along = 0.5 * ((qn[k + ck][j + cj][i + ci] - qn[k - ck][j - cj][i - ci]) +
                                  (qn[kn + ck][jn + cj][in + ci] - qn[kn - ck][jn - cj][in - ci])) / span;
      sum += across * (across + cross * along);
    }
    return mu_f * A * d * sum;
  };
  // Each interior face once from its low cell (and the faces on the block's low sides from the
  // owned cell above them), half to each owned cell; a boundary face all to its cell.
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        for (const auto& fg : cell_faces(3)) {
          const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
          if (blocked(i, j, k)) break;  // no flow in it; its walls' work is the open cells'
          if (grid_.outside(in, jn, kn) || blocked(in, jn, kn)) {
            out[k][j][i] += face_work(i, j, k, fg);
          } else if (fg.sign > 0) {
            const double w = 0.5 * face_work(i, j, k, fg);
            out[k][j][i] += w;
            if (owned(in, jn, kn)) out[kn][jn][in] += w;
          } else if (!owned(in, jn, kn)) {  // a face shared with another rank: its half of it is ours
            out[k][j][i] += 0.5 * face_work(in, jn, kn, box_faces[2 * fg.axis]);
          }
        }
  std::fill(lode_rate_.values().begin(), lode_rate_.values().end(), 0.0);
  double rate = 0.0;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        rate += out[k][j][i];
        const double theta = rheology::lode_angle(cell_strain_rate(grid_, velocity_arrays(vel), i, j, k));
        lode_rate_.add(theta * 180.0 / std::numbers::pi, out[k][j][i]);
      }
  return rate;
}

SoilBudget SoilPhase::budget_3d(const FlowSolver& flow) {
  const auto& b = grid_.owned();
  const auto& g = flow_settings_.gravity;
  const double rho_a = settings_.air_density;
  const ConstFieldArray c_array(grid_.field_dm(), c_->global()), rho_array(grid_.field_dm(), flow.density().global());
  const auto m = share_arrays(false);
  const VolumeView c = c_array.volume(), rho = rho_array.volume();
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  double s[8] = {0, 0, 0, 0, compute_dissipation_3d(flow), 0, outflow_, convected_energy_rate(flow)};
  const BlockedView mask(grid_, blocked_);
  // A periodic strip's potential energy as in 2D (soil_diagnostics.cpp): the soil's weight along x in
  // excess of the air's, its first moment run on through the join.
  const bool periodic = grid_.periodic_x();
  if (periodic) s[3] -= g[0] * join_moment_;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j, k)) continue;  // solid, not the flow's
        const double V = grid_.volume(i, j, k), cc = c[k][j][i];
        const double phase_density = cell_soil_density(m, i, j, k) * cc + rho_a * (1.0 - cc);
        double speed2 = 0.0;
        for (int a = 0; a < 3; ++a) speed2 += vel.view[a][k][j][i] * vel.view[a][k][j][i];
        s[0] += cc * V;
        s[1] += (1.0 - cc) * V;
        s[2] += 0.5 * phase_density * speed2 * V;
        s[3] += mixture::potential_energy_density(phase_density, rho_a, g, {grid_.xc(i), grid_.yc(j), grid_.zc(k)},
                                                  periodic) * V;
        s[5] += rho[k][j][i] * V;
      }
  double t[8];
  MPI_Allreduce(s, t, 8, MPI_DOUBLE, MPI_SUM, grid_.comm());
  return {t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7]};
}

}  // namespace granflow

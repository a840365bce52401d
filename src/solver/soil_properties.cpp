// The soil phase's share of the mixture's properties: the viscosity of cells and faces from the
// rheology at the yield pressure and strain rate, walls of their own friction, and the overburden.
#include "solver/soil_phase.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>

#include "io/collective_failure.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/obstacles.hpp"
#include "models/interface/material_transport.hpp"
#include "models/interface/vof_advection.hpp"
#include "models/interface/wetted_fraction.hpp"
#include "models/rheology/invariants.hpp"
#include "operators/face_interpolation.hpp"
#include "operators/strain_rate.hpp"
#include "solver/cell_faces.hpp"
#include "solver/divergence_error.hpp"

namespace granflow {

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

// One evaluation on a face at soil fraction cf between cells of soil fractions c_low and c_high and
// shares own and other. Between two soils the face is as strong as the weaker side: a slip surface
// along the contact of two materials runs on the weaker one's side (with the mean of their strengths
// a slip along a stiff foundation had to run a cell higher). A side without soil, or with a sliver
// whose shares are round-off, has no shares to give.
double SoilPhase::face_mixture_viscosity(double c_low, double c_high, double cf, double pressure,
                                         const rheology::StrainRate& rate, const Shares& own,
                                         const Shares& other) const {
  if (!materials_) return mixture_viscosity(cf, pressure, rate);
  if (!(c_high > interface::no_soil)) return mixture_viscosity(cf, pressure, rate, own.data());
  if (!(c_low > interface::no_soil) || own == other) return mixture_viscosity(cf, pressure, rate, other.data());
  return std::min(mixture_viscosity(cf, pressure, rate, own.data()), mixture_viscosity(cf, pressure, rate, other.data()));
}

void SoilPhase::set_obstacle_friction(const Field* obstacle_index,
                                      const std::vector<std::optional<rheology::WallFriction>>& friction) {
  obstacle_index_ = obstacle_index;
  obstacle_walls_.assign(friction.size(), obstacle_wall);
  for (size_t k = 0; k < friction.size(); ++k) obstacle_walls_[k].friction = friction[k];
}

// ... on the face of a wall: where the wall has a friction of its own, the soil there is no stronger
// than the wall lets it be, the wall's strength at the wall's pressure regularised at the soil's
// shear against the wall, |D_tn| of wall_rate (models/rheology/wall_friction.hpp).
double SoilPhase::wall_mixture_viscosity(double c, double pressure, const rheology::StrainRate& rate,
                                         const double* shares, const BoundaryCondition& wall,
                                         const rheology::StrainRate& wall_rate, int wall_axis) const {
  if (!wall.friction || !rheology_ || !(c > 0.0)) return mixture_viscosity(c, pressure, rate, shares);
  const double p = pressure - ambient_pressure_;
  const double own = shares ? materials_->dynamic_viscosity(rate, p, shares) : rheology_->dynamic_viscosity(rate, p);
  const double slide =
      rheology_->regularise(wall.friction->shear_strength(p), rheology::shear_against_wall(wall_rate, wall_axis));
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
  if (grid_.dimension() == 3) return update_properties_3d(flow);
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
  if (grid_.dimension() == 3) return update_face_viscosity_3d(flow);
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
        return face_mixture_viscosity(c[j][i], c[jn][in], 0.5 * (c[j][i] + c[jn][in]), pressure, rate, own, other);
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
        auto wall_velocity = [&]() -> std::array<double, 2> {
          const auto held = held_velocity(bc, grid_, side_of(axis, sign), i, j, 0);
          return {held[0], held[1]};
        };
        auto wall_rate = [&] {
          return quadratic_wall && bc.kind != BoundaryKind::atmosphere
                     ? quadratic_wall_strain_rate(grid_, u.data(), v.data(), axis, i, j, sign, wall_velocity(),
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
          return wall_mixture_viscosity(cf, pressure, rate, own_shares, bc, rate, axis);
        }
        const auto cell_rate = cell_strain_rate(grid_, u.data(), v.data(), i, j);
        if (!bc.friction) return mixture_viscosity(c[j][i], pressure, cell_rate, own_shares);
        return wall_mixture_viscosity(c[j][i], pressure, cell_rate, own_shares, bc, wall_rate(), axis);
      },
      BlockedView(grid_, blocked_).data());
}

void SoilPhase::refresh(const FlowSolver& flow) {
  if (settings_.yield_pressure == YieldPressure::lithostatic_floor) compute_overburden(flow.settings().gravity);
}

// Depth of soil above each cell centre, sum of c dy over the cells above plus half the cell's own,
// times rho_s |g|. Columns cross ranks: ColumnDepth carries the sums of the ranks above.
void SoilPhase::compute_overburden(const std::array<double, 3>& gravity) {
  if (!column_depth_) column_depth_ = std::make_unique<ColumnDepth>(grid_);
  {
    FieldArray o(grid_.field_dm(), overburden_->global());
    ConstFieldArray cf(grid_.field_dm(), c_->global());
    // Soils of several densities: the column's mass per area, c rho_s / soil.density in place of c.
    const auto m = share_arrays(false);
    const bool densities = densities_differ();
    const auto& b = grid_.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          o.volume()[k][j][i] = cf.volume()[k][j][i] * grid_.dy(j) *
                                (densities ? cell_soil_density(m, i, j, k) / settings_.soil_density : 1.0);
  }
  column_depth_->to_centre_depths(*overburden_);
  PetscCallAbort(grid_.comm(), VecScale(overburden_->global(), settings_.soil_density * std::abs(gravity[1])));
}

}  // namespace granflow

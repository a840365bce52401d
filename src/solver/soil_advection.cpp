// The soil phase carried by the flow: the region near the soil, the interface Courant number, the VoF
// sweeps of c and the materials' shares ([VoF] App. B.3), and the displacement's transport (Eq. 20).
#include "solver/soil_phase.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>

#include "io/collective_failure.hpp"
#include "mesh/axis_views.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "mesh/obstacles.hpp"
#include "models/interface/material_transport.hpp"
#include "models/interface/vof_advection.hpp"
#include "models/interface/vof_advection_3d.hpp"
#include "models/interface/wetted_fraction.hpp"
#include "models/rheology/invariants.hpp"
#include "operators/face_interpolation.hpp"
#include "operators/strain_rate.hpp"
#include "solver/cell_faces.hpp"
#include "solver/divergence_error.hpp"

namespace granflow {

const Field& SoilPhase::soil_region(int reach, double floor) const {
  // c's ghosts are current: every change of c ends with fill_fraction_ghosts. The region's own
  // domain-boundary ghosts stay 0 (set at construction); soil coming in through a boundary is in c's.
  const Field* in = c_.get();
  // An inlet's ghosts count as soil, whatever they carry: its cells are in the region, whose solve
  // takes in the inlet's flux (outside the region the air is held at rest).
  const bool inlet = has_inlet(flow_settings_.boundaries);
  if (blocked_ || inlet) {
    // c without the blocked cells' mirrors, nor the wall ghosts that mirror those: they are not
    // soil, and a rank cannot mirror a ghost cell whose open side lies beyond its ghosts, so counting
    // them made the region differ between rank layouts. A wall's ghosts mirror cells whose own 3 x 3
    // boxes count them anyway; an open side's hold the soil coming in, and stay. The first pass reads
    // this copy (region_[1], free until the second pass).
    PetscCallAbort(grid_.comm(), VecCopy(c_->local(), region_[1]->local()));
    FieldArray a(grid_.field_dm(), region_[1]->local());
    const BlockedView mask(grid_, blocked_);
    const CellBox e = grid_.with_ghosts();
    const int ny = grid_.ny(), nz = grid_.nz();
    auto open_side = [&](Side side) { return boundary(flow_settings_.boundaries, side).kind == BoundaryKind::atmosphere; };
    for (int k = e.zs; k < e.ze(); ++k)
      for (int j = e.ys; j < e.ye(); ++j)
        for (int i = e.xs; i < e.xe(); ++i) {
          const bool outside = grid_.outside(i, j, k);
          // A ghost beyond two sides (an edge's) takes the later axis's side, as the ghosts were filled.
          const Side side = k < 0 ? Side::front : k >= nz ? Side::back : j < 0 ? Side::south : j >= ny ? Side::north
                                                                        : i < 0 ? Side::west : Side::east;
          const bool inlet_face = outside && lets_in(boundary(flow_settings_.boundaries, side), grid_, side, i, j, k);
          if (inlet_face) a.volume()[k][j][i] = 1.0;
          else if (is_blocked(mask.data(), i, j, k) || (outside && !open_side(side))) a.volume()[k][j][i] = 0.0;
        }
    in = region_[1].get();
  }
  // Beyond the mesh's longer side a wider reach covers no more cells (each pass widens by one).
  const int passes = std::clamp(reach, 1, std::max({grid_.nx(), grid_.ny(), grid_.nz()}));
  for (int k = 0; k < passes; ++k) {
    Field& out = *region_[k % 2];
    {
      ConstFieldArray a(grid_.field_dm(), in->local());
      FieldArray r(grid_.field_dm(), out.global());
      if (grid_.dimension() == 3) interface::soil_region(a.volume(), grid_.owned(), r.volume(), k == 0 ? floor : 0.0);
      else interface::soil_region(a.data(), grid_.owned(), r.data(), k == 0 ? floor : 0.0);
    }
    out.scatter_to_local();
    if (k == 0 && in == region_[1].get()) {  // the copy's ghosts outside the domain: back to the region's 0
      FieldArray a(grid_.field_dm(), region_[1]->local());
      const CellBox e = grid_.with_ghosts();
      for (int kk = e.zs; kk < e.ze(); ++kk)
        for (int j = e.ys; j < e.ye(); ++j)
          for (int i = e.xs; i < e.xe(); ++i)
            if (grid_.outside(i, j, kk)) a.volume()[kk][j][i] = 0.0;
    }
    in = &out;
  }
  return *in;
}

double SoilPhase::interface_courant(const FlowSolver& flow, double dt, int substeps) const {
  if (grid_.dimension() == 3) return interface_courant_3d(flow, dt);  // over the whole mesh
  ConstFieldArray fx = local_read(grid_, flow.face_velocity(0)), fy = local_read(grid_, flow.face_velocity(1));
  // Round-off soil (interface::round_off_soil) is cleared after each advection, so c holds none here;
  // a checkpoint of an older run may, and counted it would size the step by a face of air beside it.
  ConstFieldArray region(grid_.field_dm(), soil_region(substeps, interface::round_off_soil).local());
  const double co = larger_or_nan(
      interface::max_sweep_courant(0, dt, fx.data(), grid_.dx_data(), grid_.dy_data(), grid_.owned(), radial_weights(),
                                   region.data()),
      interface::max_sweep_courant(1, dt, fy.data(), grid_.dx_data(), grid_.dy_data(), grid_.owned(), {},
                                   region.data()));
  return mpi_max(grid_.comm(), co);
}

void SoilPhase::advect(FlowSolver& flow, double dt) {
  if (grid_.dimension() == 3) return advect_3d(flow, dt);
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
    for (size_t k = 0; k < share_.size(); ++k) PetscCallAbort(grid_.comm(), VecCopy(share_[k]->global(), share_start_[k]->global()));
    sweep(first, h, *c_, *c_tmp_, true, carry_mass ? soil_through[first]->data() : nullptr, mass_through(first),
          face[first]);
    sweep(second, h, *c_tmp_, *c_, false, carry_mass ? soil_through[second]->data() : nullptr, mass_through(second),
          face[second]);
  }
  clear_round_off_soil();
  if (carry_mass) {
    // Mass flux = u rho(c_swept), the mixture density of what crossed the face: c_swept = s / u with s
    // the soil's volume flux per unit area over the step. With the linear mixture that is the phases'
    // own masses, rho_a (u - s) + rho_s s; with the arctan one the mass the time derivative takes
    // (start_density) is the same function of c, so a face fed by a pure cell carries exactly that.
    // Soils of several densities: rho_s is that of the soil that crossed (face_mass_flux).
    auto to_mass = [&](int axis, const double* const* u, int i, int j) {
      double** m = soil_through[axis]->data();
      m[j][i] = face_mass_flux(u[j][i], m[j][i], densities_differ() ? (*soil_mass_through[axis])[j][i] : 0.0, dt);
    };
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs - 1; i < b.xe(); ++i) to_mass(0, fx.data(), i, j);
    for (int j = b.ys - 1; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) to_mass(1, fy.data(), i, j);
    for (auto& through : soil_through) through.reset();  // the mass fluxes are the flow's to read now
    flow.carry_momentum_mass(dt);
  }
}

void SoilPhase::clear_round_off_soil() {
  {
    FieldArray c(grid_.field_dm(), c_->global());
    const auto& b = grid_.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          if (std::abs(c.volume()[k][j][i]) <= interface::round_off_soil) c.volume()[k][j][i] = 0.0;
  }
  fill_fraction_ghosts(*c_);
}

double SoilPhase::face_mass_flux(double u, double soil, double soil_mass, double dt) const {
  const double swept = u != 0.0 ? std::clamp(soil / (dt * u), 0.0, 1.0) : 0.0;
  if (!densities_differ()) return u * mixture_density(swept);
  const double rho_s = soil != 0.0 ? std::clamp(soil_mass / soil, lightest_soil_, heaviest_soil_) : settings_.soil_density;
  return u * mixture_density(swept, rho_s);
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
    fill_share_ghosts(from_shares ? share_tmp_ : share_);
}

// Eulerian displacement ([VoF] Eq. 20) with the soil velocity c v: donor-cell fluxes through each
// face of a cell (four on a planar mesh, six on a mesh of layers). Face areas carry the radius in
// axisymmetric geometry; with no swirl the r-component of div(c v u) has no extra hoop term, so the
// planar form holds component by component.
void SoilPhase::transport_displacement(const FlowSolver& flow, double dt) {
  if (!settings_.displacement) return;
  const auto& b = grid_.owned();
  const int dim = grid_.dimension();
  const ConstFieldArray c_array(grid_.field_dm(), c_->local());
  const VolumeView c = c_array.volume();
  const AxisViews face(grid_, [&](int a) -> const Field& { return flow.face_velocity(a); });
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  const auto faces = cell_faces(dim);
  // Outward soil flux (c v . n A)_f of face fg of cell (i, j, k).
  auto soil_flux = [&](int i, int j, int k, const FaceGeometry& fg) {
    const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
    const double cf = grid_.outside(in, jn, kn) ? c[k][j][i] : 0.5 * (c[k][j][i] + c[kn][jn][in]);
    return fg.sign * on_face(face.view, i, j, k, fg) * grid_.face_area(fg.axis, i, j, k, fg.sign) * cf;
  };
  // The donor-cell update is stable while no cell sends out more than it holds in one sweep: the
  // flow step may be longer (time.courant > 1, several VoF sweeps), so the step is split as needed.
  double most_out = 0.0;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        double out = 0.0;  // a blocked cell's faces are walls, of no flux
        for (const auto& fg : faces) out += std::max(soil_flux(i, j, k, fg), 0.0);
        most_out = std::max(most_out, out * dt / grid_.volume(i, j, k));
      }
  // A flow that runs away (the step's divergence check comes after) gets no more than a bounded count.
  constexpr double most_sweeps = 1000.0;
  const int sweeps = int(std::clamp(std::ceil(mpi_max(grid_.comm(), most_out) - 1e-12), 1.0, most_sweeps));
  const double h = dt / sweeps;
  const BlockedView mask(grid_, blocked_);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (int a = 0; a < dim; ++a) {
      const ConstFieldArray d_array(grid_.field_dm(), disp_[a]->local());
      const VolumeView d = d_array.volume();
      FieldArray dn(grid_.field_dm(), disp_new_[a]->global());
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i) {
            if (is_blocked(mask.data(), i, j, k)) {  // its local values mirror the soil's
              dn.volume()[k][j][i] = 0.0;
              continue;
            }
            double out = 0.0;  // donor-cell displacement
            for (const auto& fg : faces) {
              const double flux = soil_flux(i, j, k, fg);
              out += flux * (flux >= 0.0 ? d[k][j][i] : d[k + fg.dk][j + fg.dj][i + fg.di]);
            }
            dn.volume()[k][j][i] = d[k][j][i] + h * (c[k][j][i] * vel.view[a][k][j][i] - out / grid_.volume(i, j, k));
          }
    }
    for (int a = 0; a < dim; ++a) PetscCallAbort(grid_.comm(), VecCopy(disp_new_[a]->global(), disp_[a]->global()));
    // Every change of the displacement ends with its ghosts filled, as c's does: the next sweep reads
    // them, and a step's snapshot and a checkpoint copy the local vectors.
    fill_displacement_ghosts();
  }
}

}  // namespace granflow

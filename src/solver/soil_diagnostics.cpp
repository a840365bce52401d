// What the soil phase reports rather than what it advances: the strain and strain-rate diagnostics
// of the output ([VoF] Eqs. 13-14, [YS] Eqs. 8, 12), the dissipation and its share by Lode angle
// ([YS] Fig. 17), and the budget of volumes and energies that history.csv records.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "mesh/axis_views.hpp"
#include "mesh/gather.hpp"
#include "mesh/largest.hpp"
#include "mesh/obstacles.hpp"
#include "models/mixture/potential_energy.hpp"
#include "models/rheology/invariants.hpp"
#include "models/strain/euler_almansi.hpp"
#include "operators/strain_rate.hpp"
#include "solver/cell_faces.hpp"
#include "solver/soil_phase.hpp"

namespace granflow {

// The largest magnitude of a vector, one field per axis of the mesh, over the owned cells with
// c >= 0.5, over all ranks: hypot of the two components on a planar mesh, the root of the three
// squares on a mesh of layers.
double SoilPhase::largest_magnitude_over_soil(const Field* const components[3]) const {
  const bool layers = grid_.dimension() == 3;
  std::optional<ConstFieldArray> arrays[3];
  VolumeView q[3] = {};
  for (int a = 0; a < grid_.dimension(); ++a) q[a] = arrays[a].emplace(grid_.field_dm(), components[a]->global()).volume();
  const ConstFieldArray c_array(grid_.field_dm(), c_->global());
  const VolumeView c = c_array.volume();
  const auto& b = grid_.owned();
  double largest = 0.0;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (!(c[k][j][i] >= 0.5)) continue;
        const double x = q[0][k][j][i], y = q[1][k][j][i];
        const double size = layers ? std::sqrt(x * x + y * y + q[2][k][j][i] * q[2][k][j][i]) : std::hypot(x, y);
        largest = larger_or_nan(largest, size);  // a NaN soil is not at rest
      }
  return mpi_max(grid_.comm(), largest);
}

double SoilPhase::largest_displacement() const {
  const Field* const d[3] = {disp_[0].get(), disp_[1].get(), disp_[2].get()};
  return largest_magnitude_over_soil(d);
}

double SoilPhase::largest_speed(const FlowSolver& flow) const {
  const Field* const v[3] = {&flow.velocity(0), &flow.velocity(1), grid_.dimension() == 3 ? &flow.velocity(2) : nullptr};
  return largest_magnitude_over_soil(v);
}

void SoilPhase::compute_diagnostics(const FlowSolver& flow) {
  if (grid_.dimension() == 3) return compute_diagnostics_3d(flow);
  const auto& b = grid_.owned();
  ConstFieldArray dx(grid_.field_dm(), disp_[0]->local()), dy(grid_.field_dm(), disp_[1]->local());
  ConstFieldArray u = local_read(grid_, flow.velocity(0)), v = local_read(grid_, flow.velocity(1));
  ConstFieldArray p(grid_.field_dm(), flow.pressure().global());
  const auto overburden = overburden_if_floor();
  FieldArray en(grid_.field_dm(), strain_norm_->global()), rn(grid_.field_dm(), rate_norm_->global()),
      lo(grid_.field_dm(), lode_->global()), ratio(grid_.field_dm(), stress_ratio_->global()),
      relative(grid_.field_dm(), relative_stress_->global());
  const BlockedView mask(grid_, blocked_);
  const auto m = share_arrays(false);
  Shares shares{};
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      if (is_blocked(mask.data(), i, j, 0)) {  // no soil, no flow
        en[j][i] = rn[j][i] = lo[j][i] = relative[j][i] = 0.0;
        ratio[j][i] = 1.0;
        continue;
      }
      const double hx = grid_.xc(i + 1) - grid_.xc(i - 1), hy = grid_.yc(j + 1) - grid_.yc(j - 1);
      strain::DisplacementGradient g{(dx[j][i + 1] - dx[j][i - 1]) / hx, (dx[j + 1][i] - dx[j - 1][i]) / hy,
                                     (dy[j][i + 1] - dy[j][i - 1]) / hx, (dy[j + 1][i] - dy[j - 1][i]) / hy};
      if (grid_.axisymmetric()) g.hoop = dx[j][i] / grid_.xc(i);  // u_r / r
      strain::AlmansiStrain e;
      strain::almansi_strain(g, e);
      en[j][i] = strain::deviatoric_norm(e);
      const auto D = cell_strain_rate(grid_, u.data(), v.data(), i, j);
      rn[j][i] = rheology::norm(rheology::deviatoric(D));
      lo[j][i] = rheology::lode_angle(D) * 180.0 / std::numbers::pi;
      const double pressure = cell_yield_pressure(p[j][i], overburden.get(), i, j) - ambient_pressure_;
      if (materials_) {
        cell_shares(m, i, j, shares);
        ratio[j][i] = materials_->stress_ratio_to_drucker_prager(D, pressure, shares.data());
        relative[j][i] = materials_->relative_shear_stress(D, pressure, shares.data());
      } else {
        ratio[j][i] = rheology_ ? rheology_->stress_ratio_to_drucker_prager(D, pressure) : 1.0;
        relative[j][i] = rheology_ ? rheology_->relative_shear_stress(D, pressure) : 1.0;
      }
    }
}

// Rate of viscous dissipation, integral of 2 mu D:D, per cell, from the work the discrete viscous
// operator does face by face: the face viscosity is the operator's face mean (harmonic by default),
// the normal derivatives are compact differences across the face and the tangential one is the
// operator's average of the two cells' central differences; each interior face gives half its work to
// either cell, a wall face all of it to its cell. Axisymmetric: face areas carry the radius, and the
// hoop stress adds 2 mu (u_r/r)^2 per unit volume (mu (u_r/r)^2 without the transpose stress). A cell-centred mu 2 D:D instead weights a soft
// layer's shear with its stiff neighbour's viscosity and overstates the dissipation by the viscosity
// contrast wherever the soil yields next to rigid soil.
// Fills dissipation_ (W per metre depth, or per radian) and the local Lode-binned rates; returns the
// rank's sum.
double SoilPhase::compute_dissipation(const FlowSolver& flow) {
  const auto& b = grid_.owned();
  const int ny = grid_.ny();
  ConstFieldArray u = local_read(grid_, flow.velocity(0)), v = local_read(grid_, flow.velocity(1));
  ConstFieldArray mu = local_read(grid_, flow.viscosity());
  ConstFieldArray fmx = local_read(grid_, flow.face_viscosity(0)), fmy = local_read(grid_, flow.face_viscosity(1));
  FieldArray out(grid_.field_dm(), dissipation_->global());
  const double* const* q[2] = {u.data(), v.data()};
  // As the momentum operator has it (momentum_equation.cpp): the normal part 2 mu (mu without the
  // transpose stress), the tangential mu plus, with the transpose stress, its lagged cross term.
  const auto& num = flow_settings_.numerics;
  const double normal_factor = num.transpose_stress ? 2.0 : 1.0, cross = num.transpose_stress ? 1.0 : 0.0;
  // Work rate of a wall face of cell (i, j) on side s, with half-cell distance d and area A: the
  // wall's traction, factor mu A times the wall gradient (two-point or quadratic), times the
  // velocity relative to the wall.
  auto wall_face = [&](const BoundaryCondition& bc, Side s, int i, int j, double A) {
    const int n = normal_axis(s);
    if (bc.kind == BoundaryKind::atmosphere) return 0.0;
    const double mu_f = s == Side::west ? fmx[j][i - 1] : s == Side::east ? fmx[j][i]
                      : s == Side::south ? fmy[j - 1][i] : fmy[j][i];
    const FaceGeometry& fg = face_on(s);
    const auto held = held_velocity(bc, grid_, s, i, j, 0);
    double work = 0.0;
    for (int c = 0; c < 2; ++c) {
      if (bc.kind == BoundaryKind::slip && c != n) continue;  // no shear on a slip side
      const double wall = held[c];  // a wall's normal component is zero
      const double gradient = wall_gradient(grid_, q[c], i, j, fg, wall, num.quadratic_wall_gradient);
      work += (c == n ? normal_factor : 1.0) * mu_f * A * gradient * (q[c][j][i] - wall);
    }
    return work;
  };
  // Work rate of the interior face between (i, j) and (i+1, j).
  auto east_face = [&](int i, int j) {
    const double d = grid_.xc(i + 1) - grid_.xc(i), A = grid_.face_area(0, i, j, 1.0);
    const double hy = grid_.yc(j + 1) - grid_.yc(j - 1);
    const double g_nn = (u[j][i + 1] - u[j][i]) / d, g_tn = (v[j][i + 1] - v[j][i]) / d;
    const double g_nt = 0.5 * ((u[j + 1][i] - u[j - 1][i]) + (u[j + 1][i + 1] - u[j - 1][i + 1])) / hy;
    return fmx[j][i] * A * d * (normal_factor * g_nn * g_nn + g_tn * (g_tn + cross * g_nt));
  };
  // ... and between (i, j) and (i, j+1).
  auto north_face = [&](int i, int j) {
    const double d = grid_.yc(j + 1) - grid_.yc(j), A = grid_.face_area(1, i, j, 1.0);
    const double hx = grid_.xc(i + 1) - grid_.xc(i - 1);
    const double g_nn = (v[j + 1][i] - v[j][i]) / d, g_tn = (u[j + 1][i] - u[j][i]) / d;
    const double g_nt = 0.5 * ((v[j][i + 1] - v[j][i - 1]) + (v[j + 1][i + 1] - v[j + 1][i - 1])) / hx;
    return fmy[j][i] * A * d * (normal_factor * g_nn * g_nn + g_tn * (g_tn + cross * g_nt));
  };
  // Each face once: an owned cell takes its east and north faces and gives the neighbour its half;
  // faces on the rank's low edges are the other rank's too, which takes its own half of them.
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) out[j][i] = 0.0;
  // A face between an open and a blocked cell is a static wall of an obstacle: all its work goes to
  // the open cell, if owned. Domain sides of a blocked cell carry no flow.
  const BlockedView mask(grid_, blocked_);
  auto blocked = [&](int i, int j) { return is_blocked(mask.data(), i, j, 0); };
  auto side = [&](Side s) -> const BoundaryCondition& { return boundary(flow_settings_.boundaries, s); };
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const bool here = blocked(i, j);
      if (!grid_.outside(i + 1, j)) {  // beyond a periodic side: the first cell, through the ghost
        if (!here && !blocked(i + 1, j)) {
          const double w = 0.5 * east_face(i, j);
          out[j][i] += w;
          if (i + 1 < b.xe()) out[j][i + 1] += w;
        } else if (!here) {
          out[j][i] += wall_face(obstacle_wall, Side::east, i, j, grid_.face_area(0, i, j, 1.0));
        } else if (!blocked(i + 1, j) && i + 1 < b.xe()) {
          out[j][i + 1] += wall_face(obstacle_wall, Side::west, i + 1, j, grid_.face_area(0, i + 1, j, -1.0));
        }
      } else if (!here) {
        out[j][i] += wall_face(side(Side::east), Side::east, i, j, grid_.face_area(0, i, j, 1.0));
      }
      if (i == 0 && grid_.bounded(Side::west)) {
        if (!here) out[j][i] += wall_face(side(Side::west), Side::west, i, j, grid_.face_area(0, i, j, -1.0));
      } else if (i == b.xs && !here) {  // the face shared with the rank to the west (or the east end)
        if (!blocked(i - 1, j)) out[j][i] += 0.5 * east_face(i - 1, j);
        else out[j][i] += wall_face(obstacle_wall, Side::west, i, j, grid_.face_area(0, i, j, -1.0));
      }
      if (j + 1 < ny) {
        if (!here && !blocked(i, j + 1)) {
          const double w = 0.5 * north_face(i, j);
          out[j][i] += w;
          if (j + 1 < b.ye()) out[j + 1][i] += w;
        } else if (!here) {
          out[j][i] += wall_face(obstacle_wall, Side::north, i, j, grid_.face_area(1, i, j, 1.0));
        } else if (!blocked(i, j + 1) && j + 1 < b.ye()) {
          out[j + 1][i] += wall_face(obstacle_wall, Side::south, i, j + 1, grid_.face_area(1, i, j + 1, -1.0));
        }
      } else if (!here) {
        out[j][i] += wall_face(side(Side::north), Side::north, i, j, grid_.face_area(1, i, j, 1.0));
      }
      if (j == 0) {
        if (!here) out[j][i] += wall_face(side(Side::south), Side::south, i, j, grid_.face_area(1, i, j, -1.0));
      } else if (j == b.ys && !here) {  // the face shared with the rank to the south
        if (!blocked(i, j - 1)) out[j][i] += 0.5 * north_face(i, j - 1);
        else out[j][i] += wall_face(obstacle_wall, Side::south, i, j, grid_.face_area(1, i, j, -1.0));
      }
    }
  std::fill(lode_rate_.values().begin(), lode_rate_.values().end(), 0.0);
  double rate = 0.0;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      if (grid_.axisymmetric()) {
        const double hoop = u[j][i] / grid_.xc(i);
        out[j][i] += normal_factor * mu[j][i] * hoop * hoop * grid_.volume(i, j);  // as the momentum's hoop term
      }
      rate += out[j][i];
      const double theta = rheology::lode_angle(cell_strain_rate(grid_, u.data(), v.data(), i, j));
      lode_rate_.add(theta * 180.0 / std::numbers::pi, out[j][i]);
    }
  return rate;  // owned cells only; the caller sums over ranks
}

void SoilPhase::accumulate_lode_energy(double dt) {
  auto& e = lode_energy_.values();
  const auto& r = lode_rate_.values();
  for (size_t k = 0; k < e.size(); ++k) e[k] += r[k] * dt;
}

rheology::LodeHistogram SoilPhase::lode_energy() const {
  rheology::LodeHistogram all(lode_energy_.bins());
  MPI_Allreduce(lode_energy_.values().data(), all.values().data(), all.bins(), MPI_DOUBLE, MPI_SUM, grid_.comm());
  return all;
}

std::vector<double> SoilPhase::material_volumes() const {
  const auto& b = grid_.owned();
  ConstFieldArray c(grid_.field_dm(), c_->global());
  const auto m = share_arrays(false);
  const BlockedView mask(grid_, blocked_);
  std::vector<double> volume(share_.size() + 1, 0.0);
  for (int layer = b.zs; layer < b.ze(); ++layer)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j, layer)) continue;
        const double soil = c.volume()[layer][j][i] * grid_.volume(i, j, layer);
        double rest = soil;
        for (size_t k = 0; k < m.size(); ++k) {
          const double share = m[k].volume()[layer][j][i];
          volume[k + 1] += soil * share;
          rest -= soil * share;
        }
        volume[0] += rest;
      }
  MPI_Allreduce(MPI_IN_PLACE, volume.data(), int(volume.size()), MPI_DOUBLE, MPI_SUM, grid_.comm());
  return volume;
}

// Energies with the mass of each phase, rho_s c + rho_a (1 - c) (rho_s the cell's soils' mean by their
// shares), which the advection conserves to round-off. The mixture density of the arctan interpolation ([VoF] App. A) is heavier than that in
// partly filled cells, so its total (mixture_mass) grows as the interface spreads; energies taken with
// it would count that growth as potential energy.
SoilBudget SoilPhase::budget(const FlowSolver& flow) {
  if (grid_.dimension() == 3) return budget_3d(flow);
  const auto& b = grid_.owned();
  const auto& g = flow_settings_.gravity;
  const double rho_a = settings_.air_density;
  ConstFieldArray c(grid_.field_dm(), c_->global());
  ConstFieldArray u = local_read(grid_, flow.velocity(0)), v = local_read(grid_, flow.velocity(1));
  ConstFieldArray rho(grid_.field_dm(), flow.density().global());
  const auto m = share_arrays(false);
  double s[8] = {0, 0, 0, 0, compute_dissipation(flow), 0, outflow_, convected_energy_rate(flow)};
  const BlockedView mask(grid_, blocked_);
  // Periodic sides: the weight along x is the soil's in excess of the air's, (rho_s - rho_a) c g_x (the
  // air's own is carried by the mean pressure gradient, FlowSettings::periodic_ambient_density), and
  // the soil's first moment along x runs on through the join: what crossed it counts where it would
  // lie had the strip gone on (join_moment_). Its work is then the drop of this energy.
  const bool periodic = !grid_.bounded(Side::west);
  if (periodic) s[3] -= g[0] * join_moment_;
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      if (is_blocked(mask.data(), i, j, 0)) continue;  // solid, not the flow's
      const double V = grid_.volume(i, j);
      const double phase_density = cell_soil_density(m, i, j) * c[j][i] + rho_a * (1.0 - c[j][i]);
      s[0] += c[j][i] * V;
      s[1] += (1.0 - c[j][i]) * V;
      s[2] += 0.5 * phase_density * (u[j][i] * u[j][i] + v[j][i] * v[j][i]) * V;
      s[3] += mixture::potential_energy_density(phase_density, rho_a, g, {grid_.xc(i), grid_.yc(j), 0.0}, periodic) * V;
      s[5] += rho[j][i] * V;
    }
  double t[8];
  MPI_Allreduce(s, t, 8, MPI_DOUBLE, MPI_SUM, grid_.comm());
  return {t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7]};
}

// The kinetic and potential energy carried in through the sides per unit time, each face's outward
// velocity v_n (the one the next step's sweeps carry: over a run, the faces of each step once) times
// minus the energy density upwind of it: of the cell where the flow leaves; where it enters, of what
// enters (the ghost's c and soil, at an inlet's velocity or, through an open side, the cell's). The
// potential energy is the budget's, of the face's centre (along a periodic strip the soil's weight in
// excess of the air's). Periodic joins, walls and obstacles carry none.
double SoilPhase::convected_energy_rate(const FlowSolver& flow) const {
  const auto& b = grid_.owned();
  const int dim = grid_.dimension();
  const auto& g = flow_settings_.gravity;
  const double rho_a = settings_.air_density;
  const ConstFieldArray c_array(grid_.field_dm(), c_->local());  // ghosted: what comes in
  const VolumeView c = c_array.volume();
  const AxisViews vel(grid_, [&](int a) -> const Field& { return flow.velocity(a); });
  const AxisViews face_vel(grid_, [&](int a) -> const Field& { return flow.face_velocity(a); });
  const auto m = share_arrays(true);
  const BlockedView mask(grid_, blocked_);
  const bool periodic = grid_.periodic_x();
  double rate = 0.0;
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        if (is_blocked(mask.data(), i, j, k)) continue;
        for (const FaceGeometry& fg : cell_faces(dim)) {
          const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
          if (!grid_.outside(in, jn, kn)) continue;
          const BoundaryCondition& bc = boundary(flow_settings_.boundaries, fg.side);
          if (bc.kind != BoundaryKind::atmosphere && bc.kind != BoundaryKind::inlet) continue;
          const double outward = fg.sign * on_face(face_vel.view, i, j, k, fg);
          if (outward == 0.0) continue;
          const bool leaving = outward > 0.0;
          const int iu = leaving ? i : in, ju = leaving ? j : jn, ku = leaving ? k : kn;
          const double cu = c[ku][ju][iu];
          const double density = cell_soil_density(m, iu, ju, ku) * cu + rho_a * (1.0 - cu);
          double speed2 = 0.0;
          for (int a = 0; a < dim; ++a) {
            const double v = !leaving && bc.kind == BoundaryKind::inlet ? bc.velocity[a] : vel.view[a][k][j][i];
            speed2 += v * v;
          }
          std::array<double, 3> x{grid_.xc(i), grid_.yc(j), dim == 3 ? grid_.zc(k) : 0.0};
          x[fg.axis] += 0.5 * fg.sign * grid_.width(fg.axis, index_along(fg.axis, i, j, k));
          const double potential = mixture::potential_energy_density(density, rho_a, g, x, periodic);
          rate -= (0.5 * density * speed2 + potential) * outward * grid_.face_area(fg.axis, i, j, k, fg.sign);
        }
      }
  return rate;
}

}  // namespace granflow

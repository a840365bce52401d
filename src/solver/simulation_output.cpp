// What a run writes at its output times and after each step: the fields, the soil's surface,
// failure line and column heights, the line samples, and the history.
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/contour.hpp"
#include "io/field_sample.hpp"
#include "io/run_directory.hpp"
#include "mesh/gather.hpp"
#include "solver/simulation.hpp"

namespace granflow {

void Simulation::write_output() {
  if (out_.empty()) return;
  const Grid& g = *grid_;
  // The records of the case and of the line samples go with the first output, after a --overwrite has
  // cleared the directory of the earlier run (io/run_directory.hpp).
  if (!run_recorded_ && rank_ == 0) {
    record_run(out_, config_.output.lines);
    int ranks;
    MPI_Comm_size(g.comm(), &ranks);
    record_case(out_, config_, ranks, restarted_ ? restart_time_ : -1.0);
  }
  run_recorded_ = true;
  // The strain norm behind the failure line is a diagnostic: bring it up to date for the soil lines
  // as well as for the fields, which may be switched off.
  if (soil_) soil_->compute_diagnostics(*flow_);
  const bool layers = g.dimension() == 3;
  auto u = gather_to_root(g, flow_->velocity(0));
  auto v = gather_to_root(g, flow_->velocity(1));
  auto p = gather_to_root(g, flow_->pressure());
  // Three components as one vector field; the third is zero on a planar mesh.
  auto vector_of = [&](const std::vector<double>& x, const std::vector<double>& y, const Field* z) {
    const auto zs = z ? gather_to_root(g, *z) : std::vector<double>();
    std::vector<double> out(x.size() * 3, 0.0);
    for (size_t k = 0; k < x.size(); ++k) {
      out[3 * k] = x[k];
      out[3 * k + 1] = y[k];
      if (z) out[3 * k + 2] = zs[k];
    }
    return out;
  };
  if (config_.output.fields) {
    auto rho = gather_to_root(g, flow_->density());
    auto mu = gather_to_root(g, flow_->viscosity());
    std::vector<double> vel = vector_of(u, v, layers ? &flow_->velocity(2) : nullptr);
    std::vector<CellData> data{{"velocity", 3, vel}, {"pressure", 1, p}, {"density", 1, rho}, {"viscosity", 1, mu}};
    if (blocked_) data.push_back({"obstacle", 1, gather_to_root(g, *blocked_)});  // 1 in a blocked cell
    if (soil_) {
      std::vector<double> disp = vector_of(gather_to_root(g, soil_->displacement(0)),
                                           gather_to_root(g, soil_->displacement(1)),
                                           layers ? &soil_->displacement(2) : nullptr);
      const auto c = gather_to_root(g, soil_->soil_fraction());
      data.push_back({"soil_fraction", 1, c});
      // Each material's volume fraction c m: the soil fraction shared out (the rheology's own soil holds the rest).
      for (int k = 1; k <= soil_->material_count(); ++k) {
        auto q = gather_to_root(g, soil_->material_share(k));
        for (size_t n = 0; n < q.size(); ++n) q[n] *= c[n];
        data.push_back({"soil_fraction_" + soil_->material_name(k), 1, std::move(q)});
      }
      data.push_back({"displacement", 3, disp});
      data.push_back({"strain_norm", 1, gather_to_root(g, soil_->strain_norm())});
      data.push_back({"strain_rate_norm", 1, gather_to_root(g, soil_->strain_rate_norm())});
      data.push_back({"lode_angle", 1, gather_to_root(g, soil_->lode_angle())});
      if (config_.soil->rheology) {
        data.push_back({"stress_ratio_to_drucker_prager", 1, gather_to_root(g, soil_->stress_ratio_to_drucker_prager())});
        data.push_back({"relative_shear_stress", 1, gather_to_root(g, soil_->relative_shear_stress())});
      }
      auto w = gather_to_root(g, soil_->dissipation());  // empty on ranks other than the root
      if (!w.empty())
        for (int k = 0; k < g.nz(); ++k)
          for (int j = 0; j < g.ny(); ++j)
            for (int i = 0; i < g.nx(); ++i) w[(size_t(k) * g.ny() + j) * g.nx() + i] /= g.volume(i, j, k);
      data.push_back({"dissipation_rate", 1, w});
    }
    series_->write(g, time_, data);
  }
  if (soil_) {
    write_soil_lines();
    write_history();
    write_lode_energy();
  }
  write_line_samples(u, v, p);
  ++output_index_;
}

// Each [[output.line]]: u, v (w on a mesh of layers), p and the viscosity, and with soil its fraction,
// strain norm and strain rate norm, at evenly spaced points (io/field_sample.hpp: bilinear, trilinear
// on a mesh of layers, running to the boundary's value within half a cell of a side or an obstacle).
// u, v and p are already gathered on rank 0.
void Simulation::write_line_samples(const std::vector<double>& u, const std::vector<double>& v,
                                    const std::vector<double>& p) const {
  if (config_.output.lines.empty()) return;
  const Grid& g = *grid_;
  // The last member: the rule on an obstacle's walls (a static wall's velocity, the pressure's line
  // continued, a zero gradient for the rest).
  struct Sampled {
    const char* name;
    std::vector<double> values;
    SideRules sides;
    SideRule obstacle_wall;
  };
  const SideRule no_slip{SideRule::Kind::value, 0.0}, linear{SideRule::Kind::linear, 0.0};
  const int dimension = g.dimension();
  std::vector<Sampled> q;
  // The sides as the flow was solved (an inlet's velocity at its schedule's factor).
  const BoundarySet& sides = flow_->settings().boundaries;
  q.push_back({"u", u, velocity_side_rules(sides, 0, dimension), no_slip});
  q.push_back({"v", v, velocity_side_rules(sides, 1, dimension), no_slip});
  if (dimension == 3)
    q.push_back({"w", gather_to_root(g, flow_->velocity(2)), velocity_side_rules(sides, 2, 3), no_slip});
  q.push_back({"p", p, pressure_side_rules(), linear});
  q.push_back({"viscosity", gather_to_root(g, flow_->viscosity()), SideRules{}, SideRule{}});
  if (soil_) {
    q.push_back({"soil_fraction", gather_to_root(g, soil_->soil_fraction()), SideRules{}, SideRule{}});
    q.push_back({"strain_norm", gather_to_root(g, soil_->strain_norm()), SideRules{}, SideRule{}});
    q.push_back({"strain_rate_norm", gather_to_root(g, soil_->strain_rate_norm()), SideRules{}, SideRule{}});
  }
  if (rank_ != 0) return;
  if (blocked_)
    for (auto& s : q) fill_obstacle_walls(g, blocked_on_root_, s.obstacle_wall, s.values);
  for (const auto& line : config_.output.lines) {
    auto body = [&](std::ostream& out) {
      fmt::print(out, "# {} at t = {:.9g} s{}\nx,y{}", line.name, time_,
                 steady_state_reached_ ? ", steady state reached" : "", dimension == 3 ? ",z" : "");
      for (const auto& s : q) fmt::print(out, ",{}", s.name);
      fmt::print(out, "\n");
      for (int k = 0; k < line.points; ++k) {
        const double f = double(k) / (line.points - 1);
        const double x = line.start[0] + f * (line.end[0] - line.start[0]);
        const double y = line.start[1] + f * (line.end[1] - line.start[1]);
        const double z = line.start[2] + f * (line.end[2] - line.start[2]);
        fmt::print(out, "{:.9g},{:.9g}", x, y);
        if (dimension == 3) fmt::print(out, ",{:.9g}", z);
        const bool solid = in_blocked_cell(x, y, z);  // inside an obstacle: no flow to sample
        for (const auto& s : q)
          fmt::print(out, ",{:.12g}", solid ? std::nan("") : sample_field(g, s.values, s.sides, x, y, z));
        fmt::print(out, "\n");
      }
    };
    write_file_atomically(out_ / fmt::format("{}_{:05d}.csv", line.name, output_index_), body);
    write_file_atomically(out_ / fmt::format("{}.csv", line.name), body);
  }
}

namespace {
// Toe and wall height of the pile from the column heights h(x) = sum_j c dy (gathered on rank 0); on
// a mesh of layers, of the columns h(x, z), the largest over z of each.
struct PileShape {
  double toe_thickness = 0.0;  // largest x whose column holds at least one cell of soil
  double wall_height = 0.0;    // soil height in the first column
};
// The soil's height sum_j c dy over column (i, k) of a gathered soil fraction.
double column_height(const Grid& g, const std::vector<double>& c, int i, int k) {
  double h = 0.0;
  for (int j = 0; j < g.ny(); ++j) h += c[(size_t(k) * g.ny() + j) * g.nx() + i] * g.dy(j);
  return h;
}
// wall_column: the first column with an open cell (0 but where obstacles block whole columns at the west).
PileShape pile_shape(const Grid& g, const std::vector<double>& c, int wall_column) {
  PileShape s;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      const double h = column_height(g, c, i, k);
      // The first layer's as they are (a planar mesh's), the later layers' where they go further.
      if (i == wall_column) s.wall_height = k == 0 ? h : std::max(s.wall_height, h);
      if (h >= g.dy(0)) s.toe_thickness = k == 0 ? g.xf(i) : std::max(s.toe_thickness, g.xf(i));
    }
  return s;
}
// The layers of a gathered field, one plane [j * nx + i] each (one on a planar mesh).
std::vector<std::vector<double>> planes_of(const Grid& g, const std::vector<double>& f) {
  const size_t plane = size_t(g.nx()) * g.ny();
  std::vector<std::vector<double>> planes;
  for (int k = 0; k < g.nz(); ++k) planes.emplace_back(f.begin() + long(k * plane), f.begin() + long((k + 1) * plane));
  return planes;
}
double toe_of(const std::vector<Segment>& surface) {
  double toe = 0.0;
  for (const auto& seg : surface) toe = std::max({toe, seg.x0, seg.x1});
  return toe;
}
}  // namespace

// Whether the point lies inside the obstacles (on rank 0): in a blocked cell, and not on a face of
// it to an open cell, to round-off, where it is on the wall and is sampled.
bool Simulation::in_blocked_cell(double x, double y, double z) const {
  if (!blocked_) return false;
  const Grid& g = *grid_;
  auto index = [](int n, double v, auto&& high_face) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {  // the first cell whose high face lies beyond v
      const int mid = (lo + hi) / 2;
      if (high_face(mid) > v) hi = mid;
      else lo = mid + 1;
    }
    return lo;
  };
  const bool layers = g.dimension() == 3;
  auto blocked_at = [&](double px, double py, double pz) {
    const int i = index(g.nx(), px, [&](int k) { return g.xf(k); }), j = index(g.ny(), py, [&](int k) { return g.yf(k); });
    const int k = layers ? index(g.nz(), pz, [&](int n) { return g.zf(n); }) : 0;
    return blocked_on_root_[(size_t(k) * g.ny() + j) * g.nx() + i] > 0.5;
  };
  // A point on an obstacle's face, to round-off (a line's points are computed, as are the faces),
  // is on its wall and is sampled: only a point blocked a little way off in every direction is inside.
  const double ex = 1e-10 * (config_.mesh.upper[0] - config_.mesh.lower[0]);
  const double ey = 1e-10 * (config_.mesh.upper[1] - config_.mesh.lower[1]);
  const double ez = layers ? 1e-10 * (config_.mesh.upper[2] - config_.mesh.lower[2]) : 0.0;
  for (const double sz : {-1.0, 1.0})
    if (!(blocked_at(x - ex, y - ey, z + sz * ez) && blocked_at(x + ex, y - ey, z + sz * ez) &&
          blocked_at(x - ex, y + ey, z + sz * ez) && blocked_at(x + ex, y + ey, z + sz * ez)))
      return false;
  return true;
}

// The squares of four open cells, for the contours of the soil's surface (on rank 0): a blocked
// cell holds c = 0, and a contour through it would draw where soil rests on an obstacle. Near an
// obstacle the surface ends at the last open cells' centres, as it does at the domain's sides. Of
// one layer of a mesh of layers (0 on a planar mesh).
std::function<bool(int, int)> Simulation::open_square(int layer) const {
  if (!blocked_) return {};
  return [this, layer](int i, int j) {
    const int nx = grid_->nx();
    const size_t plane = size_t(layer) * grid_->ny() * nx;
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di)
        if (blocked_on_root_[plane + size_t(j + dj) * nx + i + di] > 0.5) return false;
    return true;
  };
}

void Simulation::record_history(double dt) {
  const SoilBudget b = soil_->budget(*flow_);
  dissipated_energy_ += b.dissipation_rate * dt;
  soil_->accumulate_lode_energy(dt);
  const auto c = gather_to_root(*grid_, soil_->soil_fraction());
  const auto [force, obstacle, side_power] = flow_->wall_forces();
  boundary_work_ += (b.convected_energy_rate + side_power) * dt;
  soil_speed_ = soil_->largest_speed(*flow_);  // what time.rest_speed reads, once per step
  const double surface_energy = surface_tension_ ? surface_tension_->surface_energy() : 0.0;
  if (rank_ != 0) return;
  const PileShape shape = pile_shape(*grid_, c, wall_column_);
  double toe_contour = 0.0;  // on a mesh of layers, the furthest of the layers' surfaces
  const auto planes = planes_of(*grid_, c);
  for (size_t k = 0; k < planes.size(); ++k)
    toe_contour = std::max(toe_contour, toe_of(iso_line(*grid_, planes[k], 0.5, open_square(int(k)))));
  std::string row =
      fmt::format("{:.12g},{:.12g},{:.15g},{:.15g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.12g},{:.15g},{:.6g},"
                  "{:.9g}",
                  time_, dt, b.soil_volume, b.air_volume, b.kinetic_energy, b.potential_energy, dissipated_energy_,
                  toe_contour, shape.toe_thickness, shape.wall_height, b.mixture_mass, b.soil_outflow, soil_speed_,
                  boundary_work_);
  // (x, y) on the four sides of a planar mesh, (x, y, z) on the six of a mesh of layers.
  if (grid_->dimension() == 2)
    for (Side side : planar_sides) row += fmt::format(",{:.12g},{:.12g}", force[int(side)][0], force[int(side)][1]);
  else
    for (const auto& f : force) row += fmt::format(",{:.12g},{:.12g},{:.12g}", f[0], f[1], f[2]);
  if (blocked_) row += fmt::format(",{:.12g},{:.12g}", obstacle[0], obstacle[1]);
  if (blocked_ && grid_->dimension() == 3) row += fmt::format(",{:.12g}", obstacle[2]);
  if (surface_tension_) row += fmt::format(",{:.9g}", surface_energy);
  history_.push_back(std::move(row));
}

void Simulation::write_history() const {
  if (rank_ != 0) return;
  write_file_atomically(out_ / "history.csv", [&](std::ostream& out) {
    fmt::print(out, "time,dt,soil_volume,air_volume,kinetic_energy,potential_energy,dissipated_energy,"
                    "toe_contour,toe_one_cell,wall_height,mixture_mass,soil_outflow,soil_speed,boundary_work");
    if (grid_->dimension() == 2)
      for (Side side : planar_sides) fmt::print(out, ",force_{0}_x,force_{0}_y", side_name(side));
    else
      for (Side side : box_sides) fmt::print(out, ",force_{0}_x,force_{0}_y,force_{0}_z", side_name(side));
    if (blocked_) fmt::print(out, ",force_obstacle_x,force_obstacle_y");
    if (blocked_ && grid_->dimension() == 3) fmt::print(out, ",force_obstacle_z");
    if (surface_tension_) fmt::print(out, ",surface_energy");
    fmt::print(out, "\n");
    for (const auto& row : history_) fmt::print(out, "{}\n", row);
  });
}

// Dissipated energy so far binned by the Lode angle of the cell that dissipated it ([YS] Fig. 17).
void Simulation::write_lode_energy() const {
  const auto h = soil_->lode_energy();
  if (rank_ != 0) return;
  write_file_atomically(out_ / "lode_dissipation.csv", [&](std::ostream& out) {
    fmt::print(out, "# energy dissipated up to t = {:.9g} s by Lode angle ({})\n", time_,
               grid_->dimension() == 3 ? "J" : grid_->axisymmetric() ? "J per radian" : "J per metre depth");
    fmt::print(out, "theta_deg,theta_low_deg,theta_high_deg,energy\n");
    for (int k = 0; k < h.bins(); ++k)
      fmt::print(out, "{:.6g},{:.6g},{:.6g},{:.9g}\n", h.centre_deg(k), h.lower_edge_deg(k), h.lower_edge_deg(k + 1),
                 h.energy(k));
  });
}

// Soil surface (c = 0.5), column heights and failure line (strain norm at its failure value, inside
// the soil) at the current time, as CSV.
void Simulation::write_soil_lines() const {
  const Grid& g = *grid_;
  const auto c = gather_to_root(g, soil_->soil_fraction());
  const auto e = gather_to_root(g, soil_->strain_norm());
  if (rank_ != 0) return;
  const std::string stamp = fmt::format("{:05d}", output_index_);
  if (g.dimension() == 3) return write_column_heights_3d(c, stamp);
  auto write_segments = [&](const std::string& name, const std::vector<Segment>& segs) {
    write_file_atomically(out_ / fmt::format("{}_{}.csv", name, stamp), [&](std::ostream& out) {
      fmt::print(out, "# {} at t = {:.9g} s\nx0,y0,x1,y1\n", name, time_);
      for (const auto& s : segs) fmt::print(out, "{:.9g},{:.9g},{:.9g},{:.9g}\n", s.x0, s.y0, s.x1, s.y1);
    });
  };
  write_segments("surface", iso_line(g, c, 0.5, open_square(0)));
  const int nx = g.nx();
  auto inside = [&](int i, int j) {
    return c[size_t(j) * nx + i] > 0.5 && c[size_t(j) * nx + i + 1] > 0.5 && c[size_t(j + 1) * nx + i] > 0.5 &&
           c[size_t(j + 1) * nx + i + 1] > 0.5;
  };
  // Without the displacement (soil.displacement = false) there is no strain, so no failure line.
  if (soil_->settings().displacement)
    write_segments("failure_line", iso_line(g, e, soil_->settings().failure_strain, inside));
  write_file_atomically(out_ / fmt::format("column_height_{}.csv", stamp), [&](std::ostream& out) {
    // With each column's east face and the floor cell's height, so that a script reads the toe of a
    // layer one cell thick as the history does, on any cells (graded, not square).
    fmt::print(out, "# soil height per column (sum of c dy) at t = {:.9g} s\nx,height,x_east,floor_cell_height\n", time_);
    for (int i = 0; i < nx; ++i)
      fmt::print(out, "{:.9g},{:.9g},{:.9g},{:.9g}\n", g.xc(i), column_height(g, c, i, 0), g.xf(i), g.dy(0));
  });
}

// On a mesh of layers: the soil's height over each (x, z) column, the surface as a height map. Its
// surface and failure line as surfaces are in the fields (a contour of soil_fraction at 0.5, of
// strain_norm at soil.failure_strain, in ParaView).
void Simulation::write_column_heights_3d(const std::vector<double>& c, const std::string& stamp) const {
  const Grid& g = *grid_;
  // With obstacles, each column's blocked height too (sum of dy over its blocked cells): the terrain.
  write_file_atomically(out_ / fmt::format("column_height_{}.csv", stamp), [&](std::ostream& out) {
    fmt::print(out, "# soil height per column (sum of c dy) at t = {:.9g} s\nx,z,height{}\n", time_,
               blocked_ ? ",obstacle_height" : "");
    for (int k = 0; k < g.nz(); ++k)
      for (int i = 0; i < g.nx(); ++i) {
        fmt::print(out, "{:.9g},{:.9g},{:.9g}", g.xc(i), g.zc(k), column_height(g, c, i, k));
        if (blocked_) fmt::print(out, ",{:.9g}", column_height(g, blocked_on_root_, i, k));
        fmt::print(out, "\n");
      }
  });
}

}  // namespace granflow

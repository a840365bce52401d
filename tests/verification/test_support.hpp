#pragma once
// Helpers shared by the solver verification tests.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/case_file.hpp"
#include "mesh/field.hpp"
#include "mesh/gather.hpp"

namespace granflow::test {

inline std::string repo_path(const std::string& rel) { return std::string(GRANFLOW_SOURCE_DIR) + "/" + rel; }

inline std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// worst = max(worst, e), but a NaN e makes it infinite (std::max would pass over it).
inline void keep_largest(double& worst, double e) {
  if (!(e <= worst)) worst = std::isnan(e) ? INFINITY : e;
}

// The largest difference between two fields gathered alike; infinite where their sizes differ or a
// difference is not a number.
inline double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) return INFINITY;
  double d = 0.0;
  for (size_t k = 0; k < a.size(); ++k) keep_largest(d, std::abs(a[k] - b[k]));
  return d;
}

// A directory for a test's run, in the build tree's tests/runs.
inline std::filesystem::path output_dir(const std::string& name) {
  return std::filesystem::path(GRANFLOW_TEST_OUTPUT_DIR) / name;
}

// The Bui et al. case (cases/bui2008_experiment.toml) at the step it had before its thin front was
// converged in the step: Courant 1 with two VoF sweeps per step, two outer iterations, the second's
// yield stress from the mean of the last two pressures. Tests of other things than that case's run-out,
// whose tolerances were measured on this set-up, put these before their own overrides (theirs win).
inline std::vector<std::string> bui2008_at_courant_one(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(), {"time.courant=1", "time.interface_substeps=2", "numerics.outer_iterations=2",
                                       "numerics.viscosity_pressure=mean_of_last_two"});
  return overrides;
}

// cases/bui2008_experiment.toml at Courant 1 (bui2008_at_courant_one) with these overrides.
inline CaseConfig bui2008_case_at_courant_one(std::vector<std::string> overrides) {
  return load_case(repo_path("cases/bui2008_experiment.toml"), bui2008_at_courant_one(std::move(overrides)));
}

// The Bui et al. case run as it was written before the coupled solve: the projection with the cells'
// mixtures, one VoF sweep per step and three outer iterations from the last step's velocity, the
// later ones' yield stress at the mean of the last two pressures. Tests whose tolerances were set on
// that set-up append these overrides to their own; they set every key bui2008_at_courant_one does.
inline std::vector<std::string> with_bui2008_projection(std::vector<std::string> overrides) {
  overrides.insert(overrides.end(), {"numerics.pressure_coupling=projection", "numerics.air_band=0",
                                     "soil.face_fraction=cells",
                                     "time.courant=0.5", "time.interface_substeps=1", "numerics.outer_iterations=3",
                                     "numerics.first_viscosity=previous_step",
                                     "numerics.viscosity_pressure=mean_of_last_two"});
  return overrides;
}

// A heavy, very viscous layer 0.1025 m deep at rest under air in a 0.2 m square box (walls but the
// open top), 32 x 32 cells, 1000 fixed steps of 1 ms: its surface cuts a row of cells at c = 0.4.
inline constexpr const char* resting_layer_case = R"(
[mesh]
cells = [32, 32]
upper = [0.2, 0.2]
[time]
end = 1e9
dt = 1e-3
adaptive = false
max_steps = 1000
[physics]
gravity = [0.0, -9.81]
[air]
density = 1.0
viscosity = 1e-5
[soil]
density = 2650.0
viscosity = 1e3
[mixture]
density = "linear"
viscosity = "linear"
[[initial.soil]]
shape = "box"
lower = [-1.0, -1.0]
upper = [1.0, 0.1025]
[boundary]
west = { type = "wall" }
east = { type = "wall" }
south = { type = "wall" }
north = { type = "atmosphere" }
[solver.momentum]
pc_type = "hypre"
[output]
progress_seconds = 0
)";

// A water drop 4 cm across falling from rest through air in a 0.2 x 0.3 m tank open at the top, under
// the coupled solve (so the conservative momentum transport), 40 x 60 cells to t = 0.12 s.
inline constexpr const char* falling_drop_case = R"(
title = "water drop falling through air"
[mesh]
cells = [40, 60]
lower = [0.0, 0.0]
upper = [0.2, 0.3]
[time]
end = 0.12
dt = 1e-4
courant = 0.25
[physics]
gravity = [0.0, -9.81]
[air]
density = 1.0
viscosity = 1.8e-5
[soil]
density = 1000.0
viscosity = 1e-3
[mixture]
density = "linear"
viscosity = "linear"
[[initial.soil]]
shape = "circle"
centre = [0.1, 0.25]
radius = 0.02
[boundary]
west = { type = "wall" }
south = { type = "wall" }
east = { type = "wall" }
north = { type = "atmosphere" }
[numerics]
convection = "blended"
blending = 0.7
outer_iterations = 2
pressure_coupling = "coupled"
[output]
fields = false
progress_seconds = 0
)";

// True on rank 0 of PETSC_COMM_WORLD, where the tests read output files and assert.
inline bool is_root() {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank == 0;
}

// A scratch directory named by rank 0's process, the same on every rank.
inline std::filesystem::path scratch(const std::string& name) {
  long pid = long(getpid());
  MPI_Bcast(&pid, 1, MPI_LONG, 0, PETSC_COMM_WORLD);
  return output_dir(name + "_" + std::to_string(pid));
}

// Removes a scratch directory from rank 0 once every rank is done with it.
inline void remove_scratch(const std::filesystem::path& dir) {
  MPI_Barrier(PETSC_COMM_WORLD);
  if (is_root()) std::filesystem::remove_all(dir);
  MPI_Barrier(PETSC_COMM_WORLD);
}

// Linear interpolation of y(x) at xq, x increasing; y's end values beyond x's ends.
inline double interp(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (xq <= x.front()) return y.front();
  if (xq >= x.back()) return y.back();
  const auto k = size_t(std::upper_bound(x.begin(), x.end(), xq) - x.begin());
  const double w = (xq - x[k - 1]) / (x[k] - x[k - 1]);
  return (1 - w) * y[k - 1] + w * y[k];
}

// Columns of a CSV file with '#' comment lines and one header line.
inline std::map<std::string, std::vector<double>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::map<std::string, std::vector<double>> cols;
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    for (size_t k = 0; k < cells.size() && k < header.size(); ++k) cols[header[k]].push_back(std::stod(cells[k]));
  }
  return cols;
}

// Sets the owned values of a field from f(x, y) at cell centres.
inline void fill(const Grid& g, Field& field, const std::function<double(double, double)>& f) {
  FieldArray a(g.field_dm(), field.global());
  const auto& b = g.owned();
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) a[j][i] = f(g.xc(i), g.yc(j));
}

// Cell-volume weighted L2 norm of (field - f) over the domain, optionally after removing the mean
// difference (pressure in a closed domain).
inline double l2_error(const Grid& g, const Field& field, const std::function<double(double, double)>& f,
                       bool remove_mean = false) {
  ConstFieldArray a(g.field_dm(), field.global());
  const auto& b = g.owned();
  double sums[3] = {0, 0, 0};  // diff*V, diff^2*V, V
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const double d = a[j][i] - f(g.xc(i), g.yc(j));
      const double V = g.volume(i, j);
      sums[0] += d * V;
      sums[1] += d * d * V;
      sums[2] += V;
    }
  double tot[3];
  MPI_Allreduce(sums, tot, 3, MPI_DOUBLE, MPI_SUM, g.comm());
  const double mean = remove_mean ? tot[0] / tot[2] : 0.0;
  return std::sqrt(std::max(tot[1] / tot[2] - mean * mean, 0.0));
}

}  // namespace granflow::test

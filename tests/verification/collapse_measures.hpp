#pragma once
// Measures shared by the collapse validation tests: how fast the soil still moves at the end of a
// run, the budgets of its history, and its last output file of a kind.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow::test {

// Largest speed over cells at least half soil, from gathered soil fraction and velocities.
inline double largest_soil_speed(const std::vector<double>& c, const std::vector<double>& u,
                                 const std::vector<double>& v) {
  double speed = 0.0;
  for (size_t k = 0; k < c.size(); ++k)
    if (c[k] >= 0.5) speed = std::max(speed, std::hypot(u[k], v[k]));
  return speed;
}

// Largest speed over the pile: the largest 4-connected set of cells at least half soil. A film of
// half a cell's thickness that has run ahead of the toe can hold a cell just above half soil and
// creep for a second more; the pile is what is asked to be at rest. Fields gathered, row-major nx x ny.
inline double largest_pile_speed(const std::vector<double>& c, const std::vector<double>& u,
                                 const std::vector<double>& v, int nx, int ny) {
  std::vector<char> seen(c.size(), 0);
  std::vector<size_t> stack;
  size_t best_size = 0;
  double best_speed = 0.0;
  for (size_t seed = 0; seed < c.size(); ++seed) {
    if (c[seed] < 0.5 || seen[seed]) continue;
    size_t size = 0;
    double speed = 0.0;
    seen[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const size_t k = stack.back();
      stack.pop_back();
      ++size;
      speed = std::max(speed, std::hypot(u[k], v[k]));
      const int i = int(k % nx), j = int(k / nx);
      const int ni[4] = {i - 1, i + 1, i, i}, nj[4] = {j, j, j - 1, j + 1};
      for (int n = 0; n < 4; ++n) {
        if (ni[n] < 0 || ni[n] >= nx || nj[n] < 0 || nj[n] >= ny) continue;
        const size_t m = size_t(nj[n]) * nx + ni[n];
        if (c[m] >= 0.5 && !seen[m]) {
          seen[m] = 1;
          stack.push_back(m);
        }
      }
    }
    if (size > best_size) {
      best_size = size;
      best_speed = speed;
    }
  }
  return best_speed;
}

// Index of the first history row at or after time t_at (the last row if none).
inline size_t first_row_at(const std::vector<double>& times, double t_at) {
  size_t k = 0;
  while (k + 1 < times.size() && times[k] < t_at) ++k;
  return k;
}

// A case run to its end: its summary, the pile's largest speed at the end, on rank 0 its
// history.csv columns, and its output directory.
struct FinishedRun {
  RunSummary summary;
  double soil_speed = 0;
  std::map<std::string, std::vector<double>> history;
  std::filesystem::path out;
};

// Collective; the speed is meaningful on rank 0.
inline FinishedRun run_to_end(const CaseConfig& config, const std::filesystem::path& out) {
  Simulation sim(PETSC_COMM_WORLD, config, out);
  FinishedRun r;
  r.summary = sim.run();
  const Grid& g = sim.grid();
  r.soil_speed = largest_pile_speed(gather_to_root(g, sim.soil()->soil_fraction()), gather_to_root(g, sim.flow().velocity(0)),
                                    gather_to_root(g, sim.flow().velocity(1)), g.nx(), g.ny());
  if (is_root()) r.history = read_csv((out / "history.csv").string());
  r.out = out;
  return r;
}

// The shipped case cases/<case_name>.toml on nx x ny cells, without a progress line and with the
// `overrides`, run to its end in a fresh directory of the build tree's tests/runs. Collective, as run_to_end. The
// directory is named for the test too: CTest runs tests side by side, and two of them running the
// same case on the same mesh must not share it.
inline FinishedRun run_shipped_case(const std::string& case_name, int nx, int ny, std::vector<std::string> overrides) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string test_name = test ? std::string("_") + test->test_suite_name() + "." + test->name() : "";
  const auto out = output_dir(case_name + "_" + std::to_string(nx) + test_name);
  std::filesystem::remove_all(out);
  overrides.push_back("output.progress_seconds=0");
  overrides.push_back("mesh.cells=[" + std::to_string(nx) + "," + std::to_string(ny) + "]");
  return run_to_end(load_case(repo_path("cases/" + case_name + ".toml"), overrides), out);
}

// Soil volume and energy over a run, from its history.csv columns.
struct CollapseBudget {
  double volume_error = 0;  // |(in the domain + carried out) / initial - 1|
  double outflow = 0;       // soil volume carried out through the open sides
  double released = 0;      // potential energy released
  double accounted = 0;     // kinetic plus dissipated energy at the end
};

inline CollapseBudget collapse_budget(std::map<std::string, std::vector<double>>& history) {
  CollapseBudget b;
  const size_t n = history["time"].size();
  if (n == 0) return b;
  b.outflow = history["soil_outflow"][n - 1];
  b.volume_error = std::abs((history["soil_volume"][n - 1] + b.outflow) / history["soil_volume"][0] - 1.0);
  b.released = history["potential_energy"][0] - history["potential_energy"][n - 1];
  b.accounted = history["kinetic_energy"][n - 1] + history["dissipated_energy"][n - 1];
  return b;
}

// Mean distance of the points (xs, ys) from the nearest of a run's line segments (columns x0, y0,
// x1, y1 of a `surface_*` or `failure_line_*` file); NaN if there are no segments, so that a check
// on it fails.
inline double mean_distance_to_segments(const std::vector<double>& xs, const std::vector<double>& ys,
                                        std::map<std::string, std::vector<double>>& segments) {
  const auto &x0 = segments["x0"], &y0 = segments["y0"], &x1 = segments["x1"], &y1 = segments["y1"];
  if (x0.empty() || xs.empty()) return std::nan("");
  double sum = 0.0;
  for (size_t k = 0; k < xs.size(); ++k) {
    double nearest = INFINITY;
    for (size_t s = 0; s < x0.size(); ++s) {
      const double ex = x1[s] - x0[s], ey = y1[s] - y0[s];
      const double t = std::clamp(((xs[k] - x0[s]) * ex + (ys[k] - y0[s]) * ey) / std::max(ex * ex + ey * ey, 1e-30), 0.0, 1.0);
      nearest = std::min(nearest, std::hypot(x0[s] + t * ex - xs[k], y0[s] + t * ey - ys[k]));
    }
    sum += nearest;
  }
  return sum / double(xs.size());
}

// The last of a run's numbered output files `prefix_NNNNN.csv`.
inline std::string last_output(const std::filesystem::path& run_dir, const std::string& prefix) {
  std::string last;
  for (const auto& e : std::filesystem::directory_iterator(run_dir))
    if (e.path().filename().string().starts_with(prefix + "_")) last = std::max(last, e.path().string());
  return last;
}

}  // namespace granflow::test

#pragma once
// Measures shared by the collapse validation tests: how fast the soil still moves at the end of a
// run, the budgets of its history, and its last output file of a kind.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/gather.hpp"
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

// The same for a simulation's current state; collective, the value is meaningful on rank 0.
inline double largest_soil_speed(Simulation& sim) {
  return largest_soil_speed(gather_to_root(sim.grid(), sim.soil()->soil_fraction()),
                            gather_to_root(sim.grid(), sim.flow().velocity(0)),
                            gather_to_root(sim.grid(), sim.flow().velocity(1)));
}

// Index of the first history row at or after time t_at (the last row if none).
inline size_t first_row_at(const std::vector<double>& times, double t_at) {
  size_t k = 0;
  while (k + 1 < times.size() && times[k] < t_at) ++k;
  return k;
}

// A case run to its end: its summary, the soil's largest speed at the end and, on rank 0, its
// history.csv columns.
struct FinishedRun {
  RunSummary summary;
  double soil_speed = 0;
  std::map<std::string, std::vector<double>> history;
};

inline FinishedRun run_to_end(const CaseConfig& config, const std::filesystem::path& out) {
  Simulation sim(PETSC_COMM_WORLD, config, out);
  FinishedRun r;
  r.summary = sim.run();
  r.soil_speed = largest_soil_speed(sim);
  if (is_root()) r.history = read_csv((out / "history.csv").string());
  return r;
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

// The last of a run's numbered output files `prefix_NNNNN.csv`.
inline std::string last_output(const std::filesystem::path& run_dir, const std::string& prefix) {
  std::string last;
  for (const auto& e : std::filesystem::directory_iterator(run_dir))
    if (e.path().filename().string().starts_with(prefix + "_")) last = std::max(last, e.path().string());
  return last;
}

}  // namespace granflow::test

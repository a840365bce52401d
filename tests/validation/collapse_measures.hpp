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

namespace granflow::test {

// Largest speed over cells at least half soil; collective, the value is meaningful on rank 0.
inline double largest_soil_speed(Simulation& sim) {
  const auto c = gather_to_root(sim.grid(), sim.soil()->soil_fraction());
  const auto u = gather_to_root(sim.grid(), sim.flow().velocity(0));
  const auto v = gather_to_root(sim.grid(), sim.flow().velocity(1));
  double speed = 0.0;
  for (size_t k = 0; k < c.size(); ++k)
    if (c[k] >= 0.5) speed = std::max(speed, std::hypot(u[k], v[k]));
  return speed;
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

#pragma once
// A layer at rest on obstacles (terrain), planar or of layers: what its run measures, for the tests
// that it stays at rest and that the terrain carries its weight.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow::test {

struct LayerOnTerrain {
  long steps = 0;
  double speed = 0.0;             // the largest at the end (m/s)
  double pressure_change = 0.0;   // the largest change over the open cells, of the largest pressure there
  double volume_change = 0.0;     // of the soil, relative
  double carried = 0.0;           // the upward force of the sides and the obstacles, of the weight
  double weight = 0.0;            // of the mixture (N, or N/m on a planar mesh)
  std::array<double, 3> obstacle{};  // the force on the obstacles
};

// Runs the case; open(x, y, z) says which cells' centres are fluid (z = 0 on a planar mesh).
inline LayerOnTerrain run_layer_on_terrain(const CaseConfig& config,
                                           const std::function<bool(double, double, double)>& open) {
  Simulation sim(PETSC_COMM_WORLD, config, "");
  const double volume0 = sim.soil()->budget(sim.flow()).soil_volume;
  const Grid& g = sim.grid();
  const auto p0 = gather_to_root(g, sim.flow().pressure());
  LayerOnTerrain o;
  o.steps = sim.run().steps;
  o.speed = sim.flow().max_speed();
  const auto p1 = gather_to_root(g, sim.flow().pressure());
  double p_scale = 0.0;  // over the open cells (a blocked cell's pressure is no fluid's)
  for (int k = 0; k < g.nz() && is_root(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        if (!open(g.xc(i), g.yc(j), g.dimension() == 3 ? g.zc(k) : 0.0)) continue;
        const size_t n = (size_t(k) * g.ny() + j) * g.nx() + i;
        p_scale = std::max(p_scale, std::abs(p0[n]));
        o.pressure_change = std::max(o.pressure_change, std::abs(p1[n] - p0[n]));
      }
  if (p_scale > 0.0) o.pressure_change /= p_scale;
  const SoilBudget b = sim.soil()->budget(sim.flow());
  o.volume_change = b.soil_volume / volume0 - 1;
  o.obstacle = sim.flow().obstacle_force();
  double vertical = o.obstacle[1];
  for (const auto& f : sim.flow().side_forces()) vertical += f[1];
  o.weight = b.mixture_mass * std::abs(config.flow.gravity[1]);
  o.carried = -vertical / o.weight;
  return o;
}

}  // namespace granflow::test

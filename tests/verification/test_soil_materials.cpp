// Soil materials in the solver: each material's volume conserved as the soil moves, its shares a
// partition of the soil, and a collapse of two materials of one strength the collapse of one soil.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

// The Bui block at 60 x 20 cells to t = 0.3 s, its lower half (y < 0.05 m) of material "lower".
std::vector<std::string> layered(double lower_friction_angle) {
  return {"mesh.cells=[60,20]", "time.end=0.3", "output.progress_seconds=0", "output.fields=false",
          "soil.materials=[{name = \"lower\", friction_angle = " + std::to_string(lower_friction_angle) + "}]",
          "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [0.2, 0.1]}, "
          "{shape = \"box\", lower = [0, 0], upper = [0.2, 0.05], material = \"lower\"}]"};
}

struct Layers {
  std::vector<double> u, v, c, share;
  double lower_volume = 0.0, upper_volume = 0.0;  // m^2 per metre
  double lower_height = 0.0, upper_height = 0.0;  // their centroids' heights, m
  double share_min = 0.0, share_max = 0.0;        // over cells with soil
};

Layers run(const std::vector<std::string>& overrides) {
  Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path("cases/bui2008_experiment.toml"), overrides), "");
  Layers r;
  auto measure = [&] {
    const Grid& g = sim.grid();
    r.u = gather_to_root(g, sim.flow().velocity(0));
    r.v = gather_to_root(g, sim.flow().velocity(1));
    r.c = gather_to_root(g, sim.soil()->soil_fraction());
    if (sim.soil()->material_count() == 0) return;
    r.share = gather_to_root(g, sim.soil()->material_share(1));
    r.lower_volume = r.upper_volume = r.lower_height = r.upper_height = 0.0;
    r.share_min = 1.0;
    r.share_max = 0.0;
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const size_t k = size_t(j) * g.nx() + i;
        const double lower = r.c[k] * r.share[k] * g.volume(i, j), upper = r.c[k] * (1.0 - r.share[k]) * g.volume(i, j);
        r.lower_volume += lower;
        r.upper_volume += upper;
        r.lower_height += lower * g.yc(j);
        r.upper_height += upper * g.yc(j);
        if (r.c[k] > 1e-9) {
          r.share_min = std::min(r.share_min, r.share[k]);
          r.share_max = std::max(r.share_max, r.share[k]);
        }
      }
    r.lower_height /= r.lower_volume;
    r.upper_height /= r.upper_volume;
  };
  measure();
  const Layers start = r;
  sim.run();
  measure();
  if (test::is_root() && sim.soil()->material_count() > 0)
    std::printf("layers: lower %.17g -> %.17g m^2, upper %.17g -> %.17g m^2; centroids %.4f / %.4f m -> %.4f / %.4f m\n",
                start.lower_volume, r.lower_volume, start.upper_volume, r.upper_volume, start.lower_height,
                start.upper_height, r.lower_height, r.upper_height);
  r.lower_volume = std::abs(r.lower_volume / start.lower_volume - 1.0);  // relative changes from here on
  r.upper_volume = std::abs(r.upper_volume / start.upper_volume - 1.0);
  return r;
}

// Two layers of the same strength: the collapse of one soil, to the round-off of mixing a yield stress
// with itself (s tau + (1 - s) tau), which the flow carries on; and each layer's volume conserved.
TEST(SoilMaterials, TwoLayersOfOneStrengthCollapseAsOneSoil) {
  const Layers one = run({"mesh.cells=[60,20]", "time.end=0.3", "output.progress_seconds=0", "output.fields=false"});
  const Layers two = run(layered(19.8));
  if (!test::is_root()) return;
  const double du = std::max(test::max_difference(one.u, two.u), test::max_difference(one.v, two.v));
  std::printf("one soil against two layers of its strength: max |du| %.2e m/s, max |dc| %.2e\n", du,
              test::max_difference(one.c, two.c));
  EXPECT_LT(du, 1e-10);  // the soil moves at up to 1 m/s; measured 3e-15
  EXPECT_LT(test::max_difference(one.c, two.c), 1e-10);
  EXPECT_LT(two.lower_volume, 1e-12);
  EXPECT_LT(two.upper_volume, 1e-12);
  EXPECT_GE(two.share_min, 0.0);
  EXPECT_LE(two.share_max, 1.0);
  EXPECT_LT(two.lower_height, two.upper_height);  // the layers keep their order
}

// A weak lower layer (phi = 10 deg against 19.8): the block slides out on it, further than the
// uniform block, and each layer's volume is conserved as the soil moves.
TEST(SoilMaterials, AWeakLowerLayerCarriesTheBlockFurther) {
  const Layers uniform = run(layered(19.8));
  const Layers weak = run(layered(10.0));
  if (!test::is_root()) return;
  auto toe = [](const Layers& r) {  // the farthest column's centre holding more than half a cell of soil
    double x = 0.0;
    for (size_t k = 0; k < 60; ++k)
      if (r.c[k] > 0.5) x = (double(k) + 0.5) * 0.01;
    return x;
  };
  std::printf("toe on the floor at t = 0.3 s: uniform %.3f m, weak lower layer %.3f m\n", toe(uniform), toe(weak));
  EXPECT_GT(toe(weak), toe(uniform) + 0.02);
  EXPECT_LT(weak.lower_volume, 1e-12);
  EXPECT_LT(weak.upper_volume, 1e-12);
  EXPECT_GE(weak.share_min, 0.0);
  EXPECT_LE(weak.share_max, 1.0);
}

}  // namespace
}  // namespace granflow

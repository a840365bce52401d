// The Eulerian displacement ([VoF] Eq. 16/20) of a rigid slug sliding along a slip channel: it must
// be the distance slid, g t^2 / 2, also with flow steps longer than a cell's crossing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

// A slug 0.4 m long in a channel 2 m x 0.1 m with slip walls, driven along x by g = 10 m/s^2, under
// air of its own density (so the slug and the air move as one body); steps of flow Courant number
// `courant`, VoF in six sweeps. Returns the soil-weighted mean and the largest |x displacement| of
// the cells with c > 0.5 at t = 0.4 s.
std::string slug_case() {
  return R"(
[mesh]
cells = [80, 4]
upper = [2.0, 0.1]
[time]
end = 0.4
dt = 1e-3
max_growth = 2.0
interface_substeps = 6
[physics]
gravity = [10.0, 0.0]
[air]
density = 1000.0
viscosity = 1e-3
[soil]
density = 1000.0
viscosity = 1e-3
displacement = true
[[initial.soil]]
shape = "box"
lower = [0.2, 0.0]
upper = [0.6, 0.1]
[boundary]
west = { type = "atmosphere" }
east = { type = "atmosphere" }
south = { type = "slip" }
north = { type = "slip" }
[output]
progress_seconds = 0
)";
}

std::pair<double, double> slide(double courant) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(slug_case(), {"time.courant=" + std::to_string(courant)}), "");
  sim.run();
  const auto c = gather_to_root(sim.grid(), sim.soil()->soil_fraction());
  const auto d = gather_to_root(sim.grid(), sim.soil()->displacement(0));
  double sum = 0.0, weight = 0.0, largest = 0.0;
  for (size_t k = 0; k < c.size(); ++k)
    if (c[k] > 0.5) {
      sum += c[k] * d[k];
      weight += c[k];
      largest = std::max(largest, std::abs(d[k]));
    }
  return {weight > 0 ? sum / weight : 0.0, largest};
}

// Measured at t = 0.4 s (slid 0.8 m): mean 0.67 / 0.74 m, largest 0.84 / 1.16 m at Courant 0.5 / 2
// (1.12 m while the open ends' inflow lost the head of the whole speed, not of the normal velocity;
// 1.20 m when that velocity was taken from the face instead of the cell).
// The upwind transport smears the slug's ends: low displacement at its rear, high at its front, where
// the conservative form of [VoF] Eq. 16 takes c at the face as the mean of a full and an empty cell, so
// the front cell gains displacement faster than it passes it on (the paper's Sec. 4.1.1 finds the same
// at the soil surface). With one explicit sweep per flow step, Courant 2 gave displacements of +-125 m
// alternating in sign. (The bound on the largest was 1.3 times the distance slid while a step taken
// again lost the displacement of the step before, 0.97 m at Courant 2.)
TEST(Displacement, SlugSlidesItsDistanceAtLongSteps) {
  const double slid = 0.5 * 10.0 * 0.4 * 0.4;
  for (double courant : {0.5, 2.0}) {
    const auto [mean, largest] = slide(courant);
    if (!test::is_root()) continue;
    std::printf("slug at Courant %.1f: mean displacement %.3f m, largest %.3f m; slid %.3f m\n", courant, mean, largest,
                slid);
    EXPECT_GT(mean, 0.8 * slid) << courant;  // 0.84 and 0.93 of it measured
    EXPECT_LT(mean, 1.0 * slid) << courant;
    EXPECT_LT(largest, 1.5 * slid) << courant;
  }
}

// A step taken again starts from the snapshot of the local vectors (ghosts included), as a checkpoint
// does: after every step, saving and restoring the soil's state must leave the displacement as it is.
// Before its ghosts were filled at the end of the transport, the snapshot held the displacement from
// before the step's last sweep, and a step taken again lost the increment of the one before.
TEST(Displacement, StepSnapshotKeepsTheDisplacement) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(slug_case(), {"time.end=0.05", "time.courant=2"}), "");
  double largest_change = 0.0, largest = 0.0;
  int steps = 0;
  sim.run([&](Simulation& s, double) {
    SoilPhase& soil = *s.soil();
    for (int a = 0; a < 2; ++a) {
      Vec before;
      VecDuplicate(soil.displacement(a).global(), &before);
      VecCopy(soil.displacement(a).global(), before);
      soil.save_state();
      soil.restore_state();
      double size = 0.0, change = 0.0;
      VecNorm(before, NORM_INFINITY, &size);
      VecAXPY(before, -1.0, soil.displacement(a).global());
      VecNorm(before, NORM_INFINITY, &change);
      VecDestroy(&before);
      largest = std::max(largest, size);
      largest_change = std::max(largest_change, change);
    }
    ++steps;
  });
  EXPECT_GT(steps, 5);
  EXPECT_GT(largest, 1e-3);  // the slug has moved: a displacement to lose
  EXPECT_EQ(largest_change, 0.0) << "largest displacement " << largest;
}

}  // namespace
}  // namespace granflow

// Soil materials on a mesh of layers (3D): a layer-independent collapse of two materials is the planar
// one; a block of two materials spreading along x and z keeps each material's volume to round-off and,
// of one strength, moves as one soil; and a bed of two densities rests with its weight on the floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

// What a run of cases/bui2008_experiment.toml leaves: velocities, c, the first material's share, each
// material's volume at the start and the end, and the energies (per metre of depth).
struct MaterialRun {
  std::vector<double> u, v, w, c, share;
  std::vector<double> volumes0, volumes;
  double kinetic = 0.0, dissipation = 0.0, mass0 = 0.0, mass = 0.0;
};

MaterialRun run(const std::vector<std::string>& overrides, double depth) {
  Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(overrides), "");
  MaterialRun r;
  if (sim.soil()->material_count() > 0) r.volumes0 = sim.soil()->material_volumes();
  r.mass0 = sim.soil()->budget(sim.flow()).mixture_mass;
  sim.run();
  const Grid& g = sim.grid();
  r.u = gather_to_root(g, sim.flow().velocity(0));
  r.v = gather_to_root(g, sim.flow().velocity(1));
  if (g.dimension() == 3) r.w = gather_to_root(g, sim.flow().velocity(2));
  r.c = gather_to_root(g, sim.soil()->soil_fraction());
  if (sim.soil()->material_count() > 0) {
    r.share = gather_to_root(g, sim.soil()->material_share(1));
    r.volumes = sim.soil()->material_volumes();
  }
  const SoilBudget b = sim.soil()->budget(sim.flow());
  r.kinetic = b.kinetic_energy / depth;
  r.dissipation = b.dissipation_rate / depth;
  r.mass = b.mixture_mass;
  return r;
}

// The largest relative change of a material's volume over the run.
double worst_volume_change(const MaterialRun& r) {
  double worst = 0.0;
  for (size_t k = 0; k < r.volumes.size(); ++k) worst = std::max(worst, std::abs(r.volumes[k] / r.volumes0[k] - 1.0));
  return worst;
}

// The relative change of the soil's volume, all materials together.
double soil_volume_change(const MaterialRun& r) {
  double now = 0.0, start = 0.0;
  for (size_t k = 0; k < r.volumes.size(); ++k) {
    now += r.volumes[k];
    start += r.volumes0[k];
  }
  return std::abs(now / start - 1.0);
}

const std::string weak_lower_layer = "soil.materials=[{name = \"lower\", friction_angle = 10.0}]";

// The Bui block with a weak lower layer (phi = 10 deg under 19.8), 60 x 20 cells to t = 0.05 s under the
// projection (whose rows do not depend on the layers beside), planar and across two layers between
// slip front and back: the materials' sweeps along x and y, their shares in the viscosity of cells and
// faces, and their volumes, are the planar ones. Measured: kinetic energy 7.6e-6 and dissipation rate
// 2e-6 of themselves apart, shares 1.0e-5 and c 1.3e-5 (the same block of one soil: c 1.3e-5, kinetic
// energy 1.6e-5; the projection's tolerances).
TEST(SoilMaterials3d, AWeakLowerLayerAcrossLayersIsThePlanarOne) {
  const std::vector<std::string> common = {
      "time.end=0.05", "output.progress_seconds=0", "output.fields=false", "numerics.pressure_coupling=\"projection\"",
      "numerics.air_band=0", weak_lower_layer};
  std::vector<std::string> planar = common, layers = common;
  planar.insert(planar.end(), {"mesh.cells=[60, 20]", "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [0.2, 0.1]}, "
                                                      "{shape = \"box\", lower = [0, 0], upper = [0.2, 0.05], material = \"lower\"}]"});
  // The lower layer a solid of its own, the upper block a planar shape extruded: the order listed holds.
  layers.insert(layers.end(), {"mesh.cells=[60, 20, 2]", "mesh.lower=[0, 0, 0]", "mesh.upper=[0.6, 0.2, 0.02]",
                               "physics.gravity=[0, -9.81, 0]", "boundary.front={type=\"slip\"}",
                               "boundary.back={type=\"slip\"}",
                               "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [0.2, 0.1]}, "
                               "{shape = \"box\", lower = [0, 0, 0], upper = [0.2, 0.05, 0.02], material = \"lower\"}]"});
  const MaterialRun flat = run(planar, 1.0), layered = run(layers, 0.02);
  if (!test::is_root()) return;
  const size_t cells = flat.c.size();
  ASSERT_EQ(layered.c.size(), 2 * cells);
  double share = 0.0, fraction = 0.0;
  for (size_t layer = 0; layer < 2; ++layer)
    for (size_t n = 0; n < cells; ++n) {
      share = std::max(share, std::abs(layered.share[layer * cells + n] - flat.share[n]));
      fraction = std::max(fraction, std::abs(layered.c[layer * cells + n] - flat.c[n]));
    }
  std::printf("weak lower layer to t = 0.05 s: kinetic energy %.9g J/m across two layers, %.9g planar; dissipation "
              "rate %.9g, %.9g W/m; largest difference of the share %.2e, of c %.2e; materials' volumes kept to %.1e, %.1e "
              "(the soil's to %.1e, %.1e)\n",
              layered.kinetic, flat.kinetic, layered.dissipation, flat.dissipation, share, fraction,
              worst_volume_change(layered), worst_volume_change(flat), soil_volume_change(layered),
              soil_volume_change(flat));
  EXPECT_NEAR(layered.kinetic / flat.kinetic, 1.0, 1e-4);
  EXPECT_NEAR(layered.dissipation / flat.dissipation, 1.0, 1e-4);
  EXPECT_LT(share, 1e-4);
  EXPECT_LT(fraction, 1e-4);
  // The soil's own volume moves by 6e-13 here on layers (the projection's divergence is its tolerance's),
  // the materials' by 8e-13 on one rank and 1e-12 on two.
  EXPECT_LT(worst_volume_change(layered), 5e-12);
}

// A block 0.2 x 0.1 m, half the channel's 6 cm deep, against the west wall and the slip front, its
// lower half (y < 0.05 m) of material "lower", 30 x 10 x 6 cells to t = 0.15 s: it spreads along x and
// along z. Of the base's strength the two materials move as one soil, to round-off; weak, each keeps its
// volume to round-off and every share stays within [0, 1].
std::vector<std::string> block_of_layers(const std::string& materials) {
  std::vector<std::string> o = {"mesh.cells=[30, 10, 6]", "mesh.lower=[0, 0, 0]", "mesh.upper=[0.6, 0.2, 0.06]",
                                "physics.gravity=[0, -9.81, 0]", "boundary.front={type=\"slip\"}",
                                "boundary.back={type=\"wall\"}", "time.end=0.15", "output.progress_seconds=0",
                                "output.fields=false"};
  if (materials.empty()) {
    o.push_back("initial.soil=[{shape = \"box\", lower = [0, 0, 0], upper = [0.2, 0.1, 0.03]}]");
  } else {
    o.push_back(materials);
    o.push_back("initial.soil=[{shape = \"box\", lower = [0, 0, 0], upper = [0.2, 0.1, 0.03]}, "
                "{shape = \"box\", lower = [0, 0, 0], upper = [0.2, 0.05, 0.03], material = \"lower\"}]");
  }
  return o;
}

TEST(SoilMaterials3d, ABlockOfTwoMaterialsSpreadingAlongXAndZKeepsEachVolume) {
  const MaterialRun one = run(block_of_layers(""), 0.06);
  const MaterialRun same = run(block_of_layers("soil.materials=[{name = \"lower\", friction_angle = 19.8}]"), 0.06);
  const MaterialRun weak = run(block_of_layers(weak_lower_layer), 0.06);
  if (!test::is_root()) return;
  const double du = std::max({test::max_difference(one.u, same.u), test::max_difference(one.v, same.v),
                              test::max_difference(one.w, same.w)});
  const double largest_w = *std::max_element(weak.w.begin(), weak.w.end());
  const auto [lowest, highest] = std::minmax_element(weak.share.begin(), weak.share.end());
  // The weak layer's reach along z: the farthest layer holding more than a tenth of a cell of it.
  int deepest = 0;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 30; ++i) {
        const size_t n = (size_t(k) * 10 + j) * 30 + i;
        if (weak.c[n] * weak.share[n] > 0.1) deepest = std::max(deepest, k);
      }
  std::printf("block of layers to t = 0.15 s: one soil against two of its strength max |du| %.2e m/s; weak lower "
              "layer: volumes kept to %.1e (one strength %.1e), shares within [%.3g, %.3g], largest w %.3f m/s, the "
              "weak soil in layer %d of 6 (its block filled 0-2)\n",
              du, worst_volume_change(weak), worst_volume_change(same), *lowest, *highest, largest_w, deepest);
  EXPECT_LT(du, 1e-10);
  EXPECT_LT(worst_volume_change(same), 1e-12);
  EXPECT_LT(worst_volume_change(weak), 1e-12);
  EXPECT_GE(*lowest, 0.0);
  EXPECT_LE(*highest, 1.0);
  EXPECT_GT(largest_w, 0.05);  // it spreads along z
  EXPECT_GE(deepest, 3);       // and the weak soil with it
}

// A bed across the channel, a heavy layer (5300 kg/m^3) 5 cm deep under 5 cm of the case's soil (2650),
// between walls on all sides, 30 x 10 x 2 cells to t = 0.1 s: the floor carries the two layers' weight
// (a mixture of one density would make it 25 % lighter), the mixture's mass is conserved, nothing moves.
TEST(SoilMaterials3d, ABedOfTwoDensitiesRestsOnTheFloorWithItsWeight) {
  const double heavy = 5300.0, light = 2650.0, air = 1.0, width = 0.6, depth = 0.02, g = 9.81;
  Simulation sim(
      PETSC_COMM_WORLD,
      test::bui2008_case_at_courant_one(
          {"mesh.cells=[30, 10, 2]", "mesh.lower=[0, 0, 0]", "mesh.upper=[0.6, 0.2, 0.02]",
           "physics.gravity=[0, -9.81, 0]", "boundary.front={type=\"wall\"}", "boundary.back={type=\"wall\"}",
           "boundary.east={type = \"wall\"}", "time.end=0.1", "output.progress_seconds=0", "output.fields=false",
           "soil.materials=[{name = \"heavy\", density = " + std::to_string(heavy) + "}]",
           "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [0.6, 0.1]}, "
           "{shape = \"box\", lower = [0, 0, 0], upper = [0.6, 0.05, 0.02], material = \"heavy\"}]"}),
      "");
  const RunSummary s = sim.run();
  const auto force = sim.flow().side_forces();
  double vertical = 0.0;
  for (const auto& f : force) vertical += f[1];
  const double weight = g * width * depth * (heavy * 0.05 + light * 0.05 + air * 0.1);
  const double mass = sim.soil()->budget(sim.flow()).mixture_mass;
  const double speed = sim.flow().max_speed();
  if (!test::is_root()) return;
  std::printf("bed of two densities on layers after %ld steps: the sides carry %.12g N, the layers weigh %.12g N; "
              "mixture mass %.12g kg against %.12g; max |v| %.2e m/s\n",
              s.steps, -vertical, weight, mass, weight / g, speed);
  EXPECT_NEAR(-vertical / weight, 1.0, 1e-9);
  EXPECT_NEAR(mass * g / weight, 1.0, 1e-12);
  EXPECT_LT(speed, 1e-6);
}

}  // namespace
}  // namespace granflow

// time.rest_speed: a run stops where its soil, having moved, has come to rest, and a soil that never
// moves runs to time.end.
#include <gtest/gtest.h>

#include <cstdio>

#include "collapse_measures.hpp"

namespace granflow {
namespace {

TEST(SoilAtRest, CollapseStopsWhereItsPileHasComeToRest) {
  // The Bui collapse on 8 mm cells: at rest by about t = 1 s (its pile moves no further to t = 2 s).
  const auto rest = test::run_shipped_case("bui2008_experiment", 75, 25,
                                           test::bui2008_at_courant_one({"time.end=5", "time.rest_speed=1e-3"}));
  const auto full = test::run_shipped_case("bui2008_experiment", 75, 25, test::bui2008_at_courant_one({"time.end=2"}));
  EXPECT_TRUE(rest.summary.soil_at_rest);
  EXPECT_FALSE(full.summary.soil_at_rest);
  if (!test::is_root()) return;
  const auto& h = rest.history;
  const auto& f = full.history;
  ASSERT_FALSE(h.at("time").empty());
  ASSERT_FALSE(f.at("time").empty());
  const double stopped = h.at("time").back();
  std::printf("[rest] stopped at t = %.3f s (%ld steps) with the pile's largest speed %.2e m/s; toe %.4f m there, "
              "%.4f m at t = 2 s\n",
              stopped, rest.summary.steps, rest.soil_speed, h.at("toe_one_cell").back(), f.at("toe_one_cell").back());
  EXPECT_GT(stopped, 0.5);  // not at the start, when the soil is still slow
  EXPECT_LT(stopped, 2.0);
  EXPECT_LT(rest.soil_speed, 1e-3);
  // The pile it stopped at is the one at t = 2 s, to a cell.
  EXPECT_NEAR(h.at("toe_one_cell").back(), f.at("toe_one_cell").back(), 0.6 / 75);
  EXPECT_NEAR(h.at("wall_height").back(), f.at("wall_height").back(), 0.2 / 25);
}

TEST(SoilAtRest, BlockThatNeverMovesRunsToTheEnd) {
  // Too cohesive to fail: slower than the rest speed from the start, but it has not moved.
  const auto block = test::run_shipped_case(
      "bui2008_experiment", 75, 25,
      test::bui2008_at_courant_one({"time.end=0.3", "time.rest_speed=1e-3", "soil.rheology.cohesion=1e5"}));
  EXPECT_FALSE(block.summary.soil_at_rest);
  EXPECT_NEAR(block.summary.time, 0.3, 1e-12);
}

}  // namespace
}  // namespace granflow

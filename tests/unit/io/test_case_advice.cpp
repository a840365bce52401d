// Advice on numerics that are known not to hold a granular pile at rest (src/io/case_advice.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/case_advice.hpp"
#include "io/case_file.hpp"

namespace granflow {
namespace {

TEST(CaseAdvice, ShippedCasesGetNone) {
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(GRANFLOW_SOURCE_DIR) + "/cases")) {
    if (entry.path().extension() != ".toml") continue;
    ++cases;
    const auto advice = case_advice(load_case(entry.path()));
    EXPECT_TRUE(advice.empty()) << entry.path() << ": " << (advice.empty() ? "" : advice[0]);
  }
  EXPECT_GE(cases, 13);
}

TEST(CaseAdvice, ExponentialRegularisationUnderTheProjectionOrWithoutTheFaceFraction) {
  const auto bui = std::string(GRANFLOW_SOURCE_DIR) + "/cases/bui2008_experiment.toml";
  const auto projection = case_advice(load_case(bui, {"numerics.pressure_coupling=projection", "numerics.air_band=0"}));
  ASSERT_EQ(projection.size(), 1u);
  EXPECT_NE(projection[0].find("numerics.pressure_coupling = \"projection\""), std::string::npos) << projection[0];
  EXPECT_EQ(case_advice(load_case(bui, {"soil.face_fraction=cells"})).size(), 1u);
  // The clipped kinematic viscosity of [YS] is left alone under the projection too: the axisymmetric
  // cases ran it so until they took the collapse's numerics.
  const auto lube = std::string(GRANFLOW_SOURCE_DIR) + "/cases/lube2004_a05.toml";
  const CaseConfig clip = load_case(lube, {"numerics.pressure_coupling=projection", "numerics.air_band=0",
                                           "soil.face_fraction=cells", "soil.yield_pressure=cell", "soil.strain_rate=cell"});
  ASSERT_TRUE(clip.soil && clip.soil->rheology);
  EXPECT_EQ(clip.soil->rheology->regularisation, rheology::Regularisation::clip);
  EXPECT_EQ(clip.flow.numerics.pressure_coupling, PressureCoupling::projection);
  EXPECT_TRUE(case_advice(clip).empty());
}

// Valid values that are most often a slip are warned of, each naming the key: no gravity, gravity
// upwards, a density in g/cm^3, a friction angle in radians.
TEST(CaseAdvice, LikelySlipsOfUnitsAndSignsAreNamed) {
  const auto bui = std::string(GRANFLOW_SOURCE_DIR) + "/cases/bui2008_experiment.toml";
  const struct {
    const char* set;
    const char* says;
  } slips[] = {
      {"physics.gravity=[0.0, 0.0]", "physics.gravity is [0, 0]"},
      {"physics.gravity=[0.0, 9.81]", "points up (+y)"},
      {"soil.density=2.65", "soil.density = 2.65 kg/m^3 is lighter than any soil"},
      {"soil.rheology.friction_angle=0.35", "friction_angle = 0.35 is in degrees: 0.35 rad would be 20.1 deg"},
      {"boundary.south={type = \"wall\", friction_angle = 0.2}",
       "boundary.south.friction_angle = 0.2 is in degrees: 0.2 rad would be 11.5 deg"},
  };
  for (const auto& slip : slips) {
    const auto advice = case_advice(load_case(bui, {slip.set, "numerics.air_band=0"}));
    ASSERT_EQ(advice.size(), 1u) << slip.set;
    EXPECT_NE(advice[0].find(slip.says), std::string::npos) << advice[0];
  }
  EXPECT_TRUE(case_advice(load_case(bui, {"physics.gravity=[4.1, -8.9]", "numerics.air_band=0"})).empty());  // a tilted bed
  EXPECT_TRUE(case_advice(load_case(bui, {"boundary.south={type = \"wall\", friction_angle = 12.0}"})).empty());
  const auto obstacle = case_advice(load_case(bui, {"obstacle=[{shape = \"box\", lower = [0.5, 0.0], upper = [0.6, 0.02], "
                                                    "friction_angle = 0.3}]"}));
  ASSERT_EQ(obstacle.size(), 1u);
  EXPECT_NE(obstacle[0].find("obstacle[0].friction_angle = 0.3 is in degrees"), std::string::npos) << obstacle[0];
  // A Newtonian pair of fluids may be driven by its walls, without gravity, and be light.
  const auto water = std::string(GRANFLOW_SOURCE_DIR) + "/cases/water_dam_break.toml";
  EXPECT_TRUE(case_advice(load_case(water, {"physics.gravity=[0.0, 0.0]", "soil.density=1.0"})).empty());
}

// A key the case gives to no effect is a warning, naming the key and what would use it.
TEST(CaseAdvice, KeysWithoutEffect) {
  const auto bui = std::string(GRANFLOW_SOURCE_DIR) + "/cases/bui2008_experiment.toml";
  const auto advice = case_advice(load_case(bui, {"numerics.pressure_correctors=3"}));
  ASSERT_EQ(advice.size(), 1u);
  EXPECT_EQ(advice[0], "numerics.pressure_correctors: used only with numerics.pressure_coupling = \"piso\"; "
                       "this case gives it to no effect");
}

// A run shortened with --set time.end keeps its output times; those past the end are not written,
// and the run's start says so.
TEST(CaseAdvice, OutputTimesPastTheEnd) {
  const auto ring = std::string(GRANFLOW_SOURCE_DIR) + "/cases/ring_collapse.toml";
  const CaseConfig c = load_case(ring, {"time.end=0.1"});
  const auto advice = case_advice(c);
  ASSERT_EQ(advice.size(), 1u);
  EXPECT_NE(advice[0].find("past time.end = 0.1 s and is not written"), std::string::npos) << advice[0];
  EXPECT_TRUE(case_advice(load_case(ring)).empty());
}

}  // namespace
}  // namespace granflow

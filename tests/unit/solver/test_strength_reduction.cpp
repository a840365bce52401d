// The case a strength-reduction trial runs: the soil's cohesion and tan(phi) divided by the factor,
// converged outer iterations, everything else the case's own.
#include "solver/strength_reduction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "io/case_error.hpp"

namespace granflow {
namespace {

const char* slope = R"(
title = "a slope"
[mesh]
cells = [20, 10]
upper = [2.0, 1.0]
[time]
end = 1.0
[air]
density = 1.0
viscosity = 1.8e-5
[soil]
density = 2000.0
[soil.rheology]
friction_angle = 30.0
cohesion = 5000.0
[boundary]
west = { type = "wall" }
east = { type = "atmosphere" }
south = { type = "wall" }
north = { type = "atmosphere" }
[[initial.soil]]
shape = "polygon"
points = [[0.0, 0.0], [1.5, 0.0], [0.5, 0.5], [0.0, 0.5]]
)";

double tan_deg(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

TEST(StrengthReduction, DividesCohesionAndTheTangentOfFriction) {
  const CaseConfig c = parse_case(slope, {"numerics.outer_iterations=2"});
  for (double factor : {0.5, 1.0, 1.37, 4.0}) {
    const CaseConfig r = reduced_strength(c, factor);
    const auto& rheology = *r.soil->rheology;
    EXPECT_NEAR(rheology.cohesion, 5000.0 / factor, 1e-12 * 5000.0);
    EXPECT_NEAR(tan_deg(rheology.friction_angle_deg), tan_deg(30.0) / factor, 1e-14);
    // As a decimal reads: the case's own 30 degrees at F = 1, not atan(tan(30 deg)) = 29.999999999999996.
    if (factor == 1.0) EXPECT_EQ(rheology.friction_angle_deg, 30.0);
    // Converged outer iterations, whatever the case asked for.
    EXPECT_EQ(r.flow.numerics.outer_iterations, 10);
    EXPECT_LE(r.flow.numerics.outer_tolerance, 1e-6);
    EXPECT_TRUE(r.soil->displacement);
    // The rest is the case's; its record holds the reduced strength and reads back to it.
    EXPECT_EQ(r.mesh.cells, c.mesh.cells);
    EXPECT_EQ(r.soil->soil_density, c.soil->soil_density);
    EXPECT_EQ(parse_case(r.as_run).soil->rheology->cohesion, rheology.cohesion);
  }
  // More iterations than ten, or a tighter tolerance, are kept.
  const CaseConfig tight = parse_case(slope, {"numerics.outer_iterations=20", "numerics.outer_tolerance=1e-8"});
  EXPECT_EQ(reduced_strength(tight, 1.2).flow.numerics.outer_iterations, 20);
  EXPECT_EQ(reduced_strength(tight, 1.2).flow.numerics.outer_tolerance, 1e-8);
}

// Every soil material's strength is divided too, and the trial keeps each shape's material and each
// material's density.
TEST(StrengthReduction, DividesEverySoilMaterialsStrength) {
  const CaseConfig c = parse_case(slope, {"soil.materials=[{name = \"clay\", friction_angle = 0.0, cohesion = 8000.0, density = 1800.5}, "
                                          "{name = \"sand\", friction_angle = 35.0, cohesion = 0.0, model = \"matsuoka_nakai\"}]",
                                          "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [2, 0.2], material = \"clay\"}, "
                                          "{shape = \"box\", lower = [0, 0.2], upper = [1, 0.4], material = \"sand\"}, "
                                          "{shape = \"box\", lower = [0, 0.4], upper = [0.5, 0.5]}]"});
  const CaseConfig r = reduced_strength(c, 1.6);
  ASSERT_EQ(r.soil->materials.size(), 2u);
  EXPECT_EQ(r.soil->materials[0].name, "clay");
  EXPECT_EQ(r.soil->materials[0].rheology.friction_angle_deg, 0.0);
  EXPECT_NEAR(r.soil->materials[0].rheology.cohesion, 5000.0, 1e-12 * 5000.0);
  EXPECT_NEAR(tan_deg(r.soil->materials[1].rheology.friction_angle_deg), tan_deg(35.0) / 1.6, 1e-14);
  EXPECT_EQ(r.soil->materials[1].rheology.cohesion, 0.0);
  EXPECT_NEAR(r.soil->rheology->cohesion, 5000.0 / 1.6, 1e-12 * 5000.0);
  EXPECT_EQ(r.soil->initial_material, (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(r.soil->materials[0].rheology.density, 1800.5);
  EXPECT_EQ(r.soil->materials[1].rheology.density, c.soil->soil_density);
  EXPECT_EQ(r.soil->materials[0].rheology.model, c.soil->rheology->model);
  EXPECT_EQ(r.soil->materials[1].rheology.model, rheology::Model::matsuoka_nakai);
}

// A wall of its own friction is an interface of the soil's: its tan(delta) and adhesion are divided too.
TEST(StrengthReduction, DividesAWallsFrictionAndAdhesion) {
  const CaseConfig c = parse_case(slope, {"soil.yield_pressure=face", "boundary.south={type = \"wall\", friction_angle = 25.0, adhesion = 300.0}",
                                          "boundary.west={type = \"wall\", adhesion = 800.0}"});
  const CaseConfig r = reduced_strength(c, 1.6);
  const auto& south = r.flow.boundaries[static_cast<int>(Side::south)].friction;
  const auto& west = r.flow.boundaries[static_cast<int>(Side::west)].friction;
  ASSERT_TRUE(south && west);
  EXPECT_NEAR(south->friction_coefficient, tan_deg(25.0) / 1.6, 1e-14);
  EXPECT_NEAR(south->adhesion, 300.0 / 1.6, 1e-12);
  EXPECT_EQ(west->friction_coefficient, 0.0);
  EXPECT_NEAR(west->adhesion, 500.0, 1e-12);
  EXPECT_FALSE(r.flow.boundaries[static_cast<int>(Side::east)].friction);
}

// ... and an obstacle's, each its own, its other keys kept (the array is rewritten in the case's text).
TEST(StrengthReduction, DividesEachObstaclesFriction) {
  const CaseConfig c = parse_case(
      slope, {"soil.yield_pressure=face", "numerics.pressure_coupling=coupled",
              "obstacle=[{shape = \"box\", lower = [1.8, 0.0], upper = [2.0, 0.3]}, "
              "{shape = \"polygon\", points = [[1.5, 0.0], [2.0, 0.0], [2.0, 0.1]], friction_angle = 20.0, adhesion = 40.0}]"});
  const CaseConfig r = reduced_strength(c, 2.0);
  ASSERT_EQ(r.obstacle_friction.size(), 2u);
  EXPECT_FALSE(r.obstacle_friction[0]);
  ASSERT_TRUE(r.obstacle_friction[1]);
  EXPECT_NEAR(r.obstacle_friction[1]->friction_coefficient, tan_deg(20.0) / 2.0, 1e-14);
  EXPECT_NEAR(r.obstacle_friction[1]->adhesion, 20.0, 1e-12);
  ASSERT_EQ(r.obstacles.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<interface::Box>(r.obstacles[0]));
  ASSERT_TRUE(std::holds_alternative<interface::Polygon>(r.obstacles[1]));
  EXPECT_EQ(std::get<interface::Polygon>(r.obstacles[1]).vertices.size(), 3u);
  EXPECT_NEAR(r.soil->rheology->cohesion, 2500.0, 1e-12);
  // Its record lists what was divided; the case as run holds it, which a run of that file reads.
  ASSERT_FALSE(r.overrides.empty());
  EXPECT_NE(r.overrides.back().find("obstacle[1].friction_angle=10"), std::string::npos) << r.overrides.back();
  EXPECT_NEAR(parse_case(r.as_run).obstacle_friction[1]->friction_coefficient, tan_deg(20.0) / 2.0, 1e-14);
}

TEST(StrengthReduction, RefusesWhatHasNoStrengthToReduce) {
  auto refusal = [](const CaseConfig& c, double factor) -> std::string {
    try {
      reduced_strength(c, factor);
    } catch (const CaseError& e) {
      return e.what();
    }
    return "";
  };
  const CaseConfig c = parse_case(slope);
  EXPECT_NE(refusal(c, 0.0).find("the factor 0 is not a positive number"), std::string::npos);
  EXPECT_NE(refusal(c, -1.0).find("not a positive number"), std::string::npos);
  const CaseConfig mu_of_i = parse_case(slope, {"soil.rheology={model = \"drucker_prager\", friction = \"mu_of_I\"}"});
  EXPECT_NE(refusal(mu_of_i, 1.0).find("mu(I) friction has none"), std::string::npos) << refusal(mu_of_i, 1.0);
  const CaseConfig grains = parse_case(slope, {"soil.materials=[{name = \"grains\", model = \"drucker_prager\", friction = \"mu_of_I\"}]",
                                               "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [1, 0.5], material = \"grains\"}]"});
  EXPECT_NE(refusal(grains, 1.0).find("the soil material 'grains' has mu(I) friction"), std::string::npos) << refusal(grains, 1.0);
  std::string without(slope);
  without.erase(without.find("[soil.rheology]"), std::string("[soil.rheology]\nfriction_angle = 30.0\ncohesion = 5000.0\n").size());
  const CaseConfig newtonian = parse_case(without, {"soil.viscosity=1e-3"});  // a Newtonian dense phase
  EXPECT_NE(refusal(newtonian, 1.0).find("needs soil with a rheology"), std::string::npos);
  const CaseConfig fed =
      parse_case(slope, {"boundary.west={type = \"inlet\", velocity = [0.1, 0.0], soil_fraction = 1.0}"});
  EXPECT_NE(refusal(fed, 1.0).find("boundary.west is an inlet: strength reduction looks for"), std::string::npos)
      << refusal(fed, 1.0);
}

}  // namespace
}  // namespace granflow

// Advice on numerics that are known not to hold a granular pile at rest (src/io/case_advice.hpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/case_advice.hpp"
#include "io/case_file.hpp"

namespace granflow {
namespace {

std::string case_path(const std::string& name) { return std::string(GRANFLOW_SOURCE_DIR) + "/cases/" + name + ".toml"; }

TEST(CaseAdvice, ShippedCasesGetNone) {
  for (const char* name : {"bui2008_experiment", "bui2008_experiment_mu_of_i", "bui2008_sph_phi25", "bui2008_sph_phi45",
                           "bui2008_sph_phi65", "bui2008_sph_phi25_c5", "lube2004_a05", "lube2004_a2", "ring_collapse",
                           "water_dam_break", "lid_driven_cavity_re100"})
    EXPECT_TRUE(case_advice(load_case(case_path(name))).empty()) << name;
}

TEST(CaseAdvice, ExponentialRegularisationUnderTheProjectionOrWithoutTheFaceFraction) {
  const auto bui = case_path("bui2008_experiment");
  const auto projection = case_advice(load_case(bui, {"numerics.pressure_coupling=projection", "numerics.air_band=0"}));
  ASSERT_EQ(projection.size(), 1u);
  EXPECT_NE(projection[0].find("numerics.pressure_coupling = \"coupled\""), std::string::npos) << projection[0];
  EXPECT_EQ(case_advice(load_case(bui, {"soil.face_fraction=cells"})).size(), 1u);
  // The clipped kinematic viscosity of [YS] is held by the projection (the axisymmetric cases).
  EXPECT_TRUE(case_advice(load_case(bui, {"numerics.pressure_coupling=projection", "numerics.air_band=0",
                                          "soil.rheology.regularisation=clip"}))
                  .empty());
}

}  // namespace
}  // namespace granflow

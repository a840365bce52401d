// The case as a run took it (CaseConfig::as_run, written as granflow_case.toml): the case file with
// its --set assignments applied, which must read back to the same case, every number to the bit.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "io/case_file.hpp"

namespace granflow {
namespace {

const char* two_phase = R"(
title = 'a "quoted" title, 0.20000000000000001 and 1.0000000000000002 kept as written'
[mesh]
cells = [12, 6]
upper = [0.30000000000000004, 0.1]
[time]
end = 0.25
dt = 1e-4
[air]
density = 1.0
viscosity = 1.8e-5
[soil]
density = 2650
[soil.rheology]
friction_angle = 19.8
m = 1e5
[boundary]
west = { type = "wall" }
east = { type = "atmosphere" }
south = { type = "wall" }
north = { type = "atmosphere" }
[[initial.soil]]
shape = "box"
lower = [0.0, 0.0]
upper = [0.1, 0.05]
)";

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(CaseRecord, NumbersAreWrittenShortestAndReadBackToTheBit) {
  const CaseConfig c = parse_case(two_phase, {"time.end=0.7", "soil.rheology.mu_min=2.5e-3"});
  const std::string& text = c.as_run;
  // Shortest forms: 0.1 + 0.2 needs all 17 digits, 0.1 one; a whole number stays a float.
  const CaseConfig whole = parse_case(two_phase, {"soil.density=2650.0"});
  EXPECT_NE(whole.as_run.find("density = 2650.0\n"), std::string::npos) << whole.as_run;
  EXPECT_NE(text.find("density = 2650\n"), std::string::npos) << text;  // an integer stays one
  EXPECT_NE(text.find("upper = [ 0.30000000000000004, 0.1 ]"), std::string::npos) << text;
  EXPECT_NE(text.find("end = 0.7"), std::string::npos) << text;
  EXPECT_NE(text.find("mu_min = 0.0025\n"), std::string::npos) << text;
  EXPECT_NE(text.find("m = 1e+05\n"), std::string::npos) << text;
  EXPECT_NE(text.find("friction_angle = 19.8\n"), std::string::npos) << text;
  // Strings are written through as they are, numbers in them included.
  EXPECT_NE(text.find("\"quoted\" title, 0.20000000000000001 and 1.0000000000000002 kept as written"),
            std::string::npos) << text;
  const CaseConfig again = parse_case(text);
  EXPECT_EQ(again.as_run, text);
  EXPECT_TRUE(same_bits(again.mesh.upper[0], 0.1 + 0.2));
  EXPECT_TRUE(same_bits(again.time.end, 0.7));
  EXPECT_TRUE(same_bits(again.soil->rheology->min_dynamic_viscosity, 2.5e-3));
  EXPECT_EQ(again.title, c.title);
}

// A title over two lines with an apostrophe is written as a multi-line string, which the numbers'
// rewriting passes over whole; the comment lines of the record keep a --set over two lines on one.
TEST(CaseRecord, MultiLineStringsAreWrittenThrough) {
  const CaseConfig c = parse_case(two_phase, {"title=\"it's\\nx 2.50 y 0.20000000000000001\"", "time.end=0.7"});
  EXPECT_NE(c.as_run.find("x 2.50 y 0.20000000000000001"), std::string::npos) << c.as_run;
  EXPECT_NE(c.as_run.find("end = 0.7"), std::string::npos) << c.as_run;  // numbers after it are still rewritten
  const CaseConfig again = parse_case(c.as_run);
  EXPECT_EQ(again.title, "it's\nx 2.50 y 0.20000000000000001");
  EXPECT_EQ(again.as_run, c.as_run);
}

// Each shipped case, with an assignment, reads back to itself: the record runs the same case.
TEST(CaseRecord, EveryShippedCaseReadsBackToItself) {
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(GRANFLOW_SOURCE_DIR) + "/cases")) {
    if (entry.path().extension() != ".toml") continue;
    ++cases;
    const CaseConfig c = load_case(entry.path(), {"time.end=0.123456789"});
    EXPECT_EQ(c.overrides, std::vector<std::string>{"time.end=0.123456789"});
    const CaseConfig again = parse_case(c.as_run);
    EXPECT_EQ(again.as_run, c.as_run) << entry.path();
    EXPECT_EQ(again.time.end, 0.123456789) << entry.path();
    EXPECT_EQ(again.mesh.cells, c.mesh.cells) << entry.path();
    EXPECT_EQ(again.title, c.title) << entry.path();
  }
  EXPECT_GE(cases, 15);
}

}  // namespace
}  // namespace granflow

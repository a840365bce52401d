// Case files: every key is checked; bad input gets one message naming the key.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <variant>

#include <unistd.h>

#include "io/case_error.hpp"
#include "io/case_file.hpp"
#include "io/text_file.hpp"

namespace granflow {
namespace {

const char* minimal = R"(
[mesh]
cells = [8, 8]
upper = [1.0, 1.0]
[time]
end = 1.0
[fluid]
density = 1.0
viscosity = 0.01
[boundary]
west = { type = "wall" }
east = { type = "wall" }
south = { type = "wall" }
north = { type = "wall", velocity = [1.0, 0.0] }
)";

// The message of the CaseError thrown for `text` with `overrides` (read as the file `source`), or "" if none.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {},
                     const std::filesystem::path& source = "<string>") {
  try {
    parse_case(text, overrides, source);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

TEST(CaseFile, MinimalCaseIsValid) {
  const CaseConfig c = parse_case(minimal);
  EXPECT_EQ(c.mesh.cells[0], 8);
  EXPECT_DOUBLE_EQ(c.fluid.viscosity, 0.01);
  EXPECT_DOUBLE_EQ(c.flow.boundaries[int(Side::north)].velocity[0], 1.0);
}

TEST(CaseFile, MisspeltKeyIsNamed) {
  const std::string e = error_of(std::string(minimal) + "[numerics]\nconvection_scheme = \"quick\"\n");
  EXPECT_NE(e.find("numerics.convection_scheme"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

// A key granflow once read and no longer does is named with why, not listed as unknown.
TEST(CaseFile, RemovedKeyIsNamedWithWhy) {
  const std::string e = error_of(std::string(minimal) + "[numerics]\nrotational_coefficient = 1.0\n");
  EXPECT_EQ(e.find("numerics.rotational_coefficient: removed; the projection's rotational pressure correction "
                   "diverged"),
            0u)
      << e;
  EXPECT_NE(e.find("Leave the key out"), std::string::npos) << e;
}

TEST(CaseFile, UnknownTableIsNamed) {
  const std::string e = error_of(std::string(minimal) + "[numerix]\n");
  EXPECT_NE(e.find("numerix"), std::string::npos) << e;
}

TEST(CaseFile, NegativeDensityIsRejected) {
  const std::string e = error_of(minimal, {"fluid.density=-1"});
  EXPECT_NE(e.find("fluid.density"), std::string::npos) << e;
}

TEST(CaseFile, EmptyDomainIsRejected) {
  const std::string e = error_of(minimal, {"mesh.upper=[0.0, 1.0]"});
  EXPECT_NE(e.find("mesh.upper"), std::string::npos) << e;
  EXPECT_NE(e.find("empty"), std::string::npos) << e;
}

// Cells below a nanometre, or too narrow for their coordinates' double precision, are refused;
// a micrometre cell at the origin and a metre cell 1e8 m out are not.
TEST(CaseFile, CellsTooSmallForTheirCoordinatesAreRejected) {
  const std::string tiny = error_of(minimal, {"mesh.upper=[1e-25, 1.0]"});
  EXPECT_NE(tiny.find("cells 1.25e-26 m wide along x, narrower than a nanometre"), std::string::npos) << tiny;
  const std::string far = error_of(minimal, {"mesh.lower=[0.0, 1e9]", "mesh.upper=[1.0, 1.000000001e9]"});
  EXPECT_NE(far.find("along y at coordinates up to 1e+09 m"), std::string::npos) << far;
  EXPECT_NO_THROW(parse_case(minimal, {"mesh.upper=[8e-6, 1.0]"}));
  EXPECT_NO_THROW(parse_case(minimal, {"mesh.lower=[0.0, 1e8]", "mesh.upper=[8.0, 1.00000008e8]"}));
}

TEST(CaseFile, WrongTypeIsNamed) {
  const std::string e = error_of(minimal, {"time.end=\"soon\""});
  EXPECT_NE(e.find("time.end"), std::string::npos) << e;
}

TEST(CaseFile, BadChoiceListsTheAllowedValues) {
  const std::string e = error_of(minimal, {"numerics.convection=superbee"});
  EXPECT_NE(e.find("numerics.convection"), std::string::npos) << e;
  EXPECT_NE(e.find("quick"), std::string::npos) << e;
}

TEST(CaseFile, SetOverridesAnyKey) {
  const CaseConfig c = parse_case(minimal, {"mesh.cells=[16,4]", "time.end=2.5", "numerics.convection=upwind"});
  EXPECT_EQ(c.mesh.cells[0], 16);
  EXPECT_EQ(c.mesh.cells[1], 4);
  EXPECT_DOUBLE_EQ(c.time.end, 2.5);
  EXPECT_EQ(c.flow.numerics.convection, ConvectionScheme::upwind);
}

TEST(CaseFile, SymmetryIsASlipWall) {
  const CaseConfig c = parse_case(minimal, {"boundary.west={type=\"symmetry\"}", "boundary.east={type=\"slip\"}"});
  EXPECT_EQ(c.flow.boundaries[int(Side::west)].kind, BoundaryKind::slip);
  EXPECT_EQ(c.flow.boundaries[int(Side::east)].kind, BoundaryKind::slip);
  EXPECT_EQ(c.flow.boundaries[int(Side::south)].kind, BoundaryKind::wall);
  // A symmetry plane takes no wall velocity.
  const std::string e = error_of(minimal, {"boundary.west={type=\"symmetry\", velocity=[0.0, 1.0]}"});
  EXPECT_NE(e.find("boundary.west.velocity"), std::string::npos) << e;
}

TEST(CaseFile, MissingSideIsNamed) {
  std::string text = minimal;
  text.erase(text.find("south ="), std::string("south = { type = \"wall\" }\n").size());
  const std::string e = error_of(text);
  EXPECT_NE(e.find("boundary.south"), std::string::npos) << e;
}

TEST(CaseFile, SyntaxErrorGivesLine) {
  const std::string e = error_of("[mesh\ncells = 3");
  EXPECT_NE(e.find(":1:"), std::string::npos) << e;
}

// Soil under air in a box open at the top; its friction angle is out of range until overridden.
const char* two_phase = R"(
[mesh]
cells = [8, 8]
upper = [1.0, 1.0]
[time]
end = 1.0
[air]
density = 1.0
viscosity = 1e-5
[soil]
density = 2650.0
[soil.rheology]
model = "drucker_prager_bingham"
friction_angle = 95.0
[[initial.soil]]
shape = "box"
lower = [0.0, 0.0]
upper = [0.5, 0.5]
[boundary]
west = { type = "wall" }
east = { type = "wall" }
south = { type = "wall" }
north = { type = "atmosphere" }
)";

// An inlet: a velocity into the domain, the soil it carries below a depth, of a material.
TEST(CaseFile, AnInletReadsItsVelocitySoilDepthAndMaterial) {
  const std::vector<std::string> open_east{"soil.rheology.friction_angle=30", "boundary.east={type = \"atmosphere\"}"};
  auto with = [&](const std::string& west) {
    auto o = open_east;
    o.push_back("boundary.west=" + west);
    return o;
  };
  const CaseConfig c = parse_case(
      std::string(two_phase) + "[[soil.materials]]\nname = \"weak\"\nfriction_angle = 10.0\n",
      with("{type = \"inlet\", velocity = [0.5, 0.1], soil_fraction = 0.6, soil_depth = 0.2, material = \"weak\"}"));
  const BoundaryCondition& west = boundary(c.flow.boundaries, Side::west);
  EXPECT_EQ(west.kind, BoundaryKind::inlet);
  EXPECT_EQ(west.velocity[0], 0.5);
  EXPECT_EQ(west.velocity[1], 0.1);
  EXPECT_EQ(west.inflow_soil_fraction, 0.6);
  EXPECT_EQ(west.inflow_soil_depth, 0.2);
  EXPECT_EQ(west.inflow_material, 1);
  // The ghost of a face half below the depth carries half the soil fraction; above it none.
  EXPECT_DOUBLE_EQ(inlet_face_soil_fraction(west, 0.15, 0.25, 0.0), 0.3);
  EXPECT_EQ(inlet_face_soil_fraction(west, 0.25, 0.35, 0.0), 0.0);
  EXPECT_EQ(inlet_face_soil_fraction(west, 0.0, 0.1, 0.0), 0.6);
  // Without a depth the whole side carries soil; without soil_fraction, air.
  const CaseConfig whole =
      parse_case(two_phase, with("{type = \"inlet\", velocity = [0.5, 0.0], soil_fraction = 1.0}"));
  EXPECT_EQ(inlet_face_soil_fraction(boundary(whole.flow.boundaries, Side::west), 0.9, 1.0, 0.0), 1.0);
  const CaseConfig air = parse_case(two_phase, with("{type = \"inlet\", velocity = [0.5, 0.0]}"));
  EXPECT_EQ(boundary(air.flow.boundaries, Side::west).inflow_soil_fraction, 0.0);
  // A domain may start empty when an inlet brings soil, and a material may come only by an inlet.
  std::string empty = two_phase;
  const std::string shape = "[[initial.soil]]\nshape = \"box\"\nlower = [0.0, 0.0]\nupper = [0.5, 0.5]\n";
  empty.replace(empty.find(shape), shape.size(), "");
  EXPECT_NO_THROW(parse_case(empty, with("{type = \"inlet\", velocity = [0.5, 0.0], soil_fraction = 1.0}")));
  const std::string no_soil = error_of(empty, with("{type = \"inlet\", velocity = [0.5, 0.0]}"));
  EXPECT_NE(no_soil.find("initial: missing table [[initial.soil]]"), std::string::npos) << no_soil;
  EXPECT_NE(no_soil.find("inlet of soil"), std::string::npos) << no_soil;
  // On the east side the inflow runs along -x.
  auto east_inlet = open_east;
  east_inlet.back() = "boundary.east={type = \"inlet\", velocity = [-0.5, 0.0]}";
  east_inlet.push_back("boundary.west={type = \"atmosphere\"}");
  EXPECT_NO_THROW(parse_case(two_phase, east_inlet));
}

// An inlet's schedule: its velocity by time, linear between pairs, a jump at a time given twice.
TEST(CaseFile, AnInletsScheduleScalesItsVelocityByTime) {
  const CaseConfig c = parse_case(
      two_phase, {"soil.rheology.friction_angle=30", "boundary.east={type = \"atmosphere\"}",
                  "boundary.west={type = \"inlet\", velocity = [0.5, 0.0], schedule = [[0.5, 0.2], [1.0, 1.0], "
                  "[2.0, 1.0], [2.0, 0.0]]}"});
  const auto& schedule = boundary(c.flow.boundaries, Side::west).inflow_schedule;
  ASSERT_EQ(schedule.size(), 4u);
  EXPECT_EQ(boundary(c.flow.boundaries, Side::west).inflow_velocity[0], 0.5);
  EXPECT_EQ(inflow_factor(schedule, 0.0), 0.2);  // the first factor before the first time
  EXPECT_EQ(inflow_factor(schedule, 0.5), 0.2);
  EXPECT_DOUBLE_EQ(inflow_factor(schedule, 0.75), 0.6);
  EXPECT_EQ(inflow_factor(schedule, 1.5), 1.0);
  EXPECT_EQ(inflow_factor(schedule, std::nextafter(2.0, 0.0)), 1.0);
  EXPECT_EQ(inflow_factor(schedule, 2.0), 0.0);  // from the jump's time on, its later factor
  EXPECT_EQ(inflow_factor(schedule, 7.0), 0.0);
  EXPECT_EQ(inflow_factor({}, 3.0), 1.0);
  // Steps land on the schedule's times, each once.
  EXPECT_EQ(next_inflow_time(c.flow.boundaries, 0.0), 0.5);
  EXPECT_EQ(next_inflow_time(c.flow.boundaries, 0.5), 1.0);
  EXPECT_EQ(next_inflow_time(c.flow.boundaries, 1.2), 2.0);
  EXPECT_TRUE(std::isinf(next_inflow_time(c.flow.boundaries, 2.0)));
  auto refusal = [&](const std::string& schedule_text) {
    const std::string west =
        "boundary.west={type = \"inlet\", velocity = [0.5, 0.0], schedule = " + schedule_text + "}";
    return error_of(two_phase, {"soil.rheology.friction_angle=30", "boundary.east={type = \"atmosphere\"}", west});
  };
  EXPECT_NE(refusal("[[1.0, 1.0], [0.5, 0.0]]").find("boundary.west.schedule: the times must not decrease (pair 1 at "
                                                      "0.5 s after pair 0 at 1 s)"), std::string::npos);
  EXPECT_NE(refusal("[[0.0, -1.0]]").find("boundary.west.schedule: the factor of pair 0 is -1"), std::string::npos);
  EXPECT_NE(refusal("[[-1.0, 1.0]]").find("the time of pair 0 is -1 s"), std::string::npos);
  EXPECT_NE(refusal("[[1.0, 1.0], [1.0, 0.0], [1.0, 1.0]]").find("three pairs at 1 s"), std::string::npos);
  EXPECT_NE(refusal("[]").find("boundary.west.schedule"), std::string::npos);
  EXPECT_NE(refusal("[1.0, 2.0]").find("boundary.west.schedule"), std::string::npos);
}

// An inlet open over part of its side: span_y on the west side (and span_x on the north), [low, high];
// a face of the side takes its open share (by r dr along an axisymmetric mesh's radius), and the soil
// fraction of its opening below the soil depth.
TEST(CaseFile, AnInletOpensOverItsSpan) {
  const std::vector<std::string> open_east{"soil.rheology.friction_angle=30", "boundary.east={type = \"atmosphere\"}"};
  auto with = [&](const std::string& west, std::vector<std::string> more = {}) {
    auto o = open_east;
    o.push_back("boundary.west=" + west);
    o.insert(o.end(), more.begin(), more.end());
    return o;
  };
  const CaseConfig c = parse_case(
      two_phase, with("{type = \"inlet\", velocity = [0.5, 0.1], soil_fraction = 0.6, soil_depth = 0.3, "
                      "span_y = [0.1875, 0.5]}"));
  const BoundaryCondition& west = boundary(c.flow.boundaries, Side::west);
  EXPECT_EQ(west.inflow_span[1][0], 0.1875);
  EXPECT_EQ(west.inflow_span[1][1], 0.5);
  EXPECT_TRUE(opens_in_part(west));
  EXPECT_FALSE(opens_in_part(boundary(c.flow.boundaries, Side::south)));
  const Grid g(PETSC_COMM_SELF, c.mesh);  // cells of 1/8 m: the span cuts the second one in half
  EXPECT_EQ(open_share(west, g, Side::west, 0, 0, 0), 0.0);
  EXPECT_EQ(open_share(west, g, Side::west, 0, 1, 0), 0.5);
  EXPECT_EQ(open_share(west, g, Side::west, 0, 2, 0), 1.0);
  EXPECT_EQ(open_share(west, g, Side::west, 0, 4, 0), 0.0);
  EXPECT_EQ(imposed_normal_velocity(west, g, Side::west, 0, 1, 0), 0.25);
  EXPECT_EQ(held_velocity(west, g, Side::west, 0, 1, 0)[1], 0.05);
  EXPECT_FALSE(lets_in(west, g, Side::west, 0, 0, 0));
  EXPECT_TRUE(lets_in(west, g, Side::west, 0, 1, 0));
  // The face [0.125, 0.25]: open from 0.1875, soil up to 0.3; [0.25, 0.375]: soil in the lower 0.05 of it.
  EXPECT_DOUBLE_EQ(inlet_face_soil_fraction(west, 0.125, 0.25, 0.0), 0.6);
  EXPECT_DOUBLE_EQ(inlet_face_soil_fraction(west, 0.25, 0.375, 0.0), 0.6 * 0.4);
  // The top's opening about the axis of an axisymmetric mesh: by r dr, (0.1875^2 - 0.125^2) / (0.25^2 - 0.125^2).
  const CaseConfig hole = parse_case(
      two_phase, with("{type = \"axis\"}", {"mesh.geometry = \"axisymmetric\"",
                                            "boundary.north={type = \"inlet\", velocity = [0.0, -1.0], span_x = [0.0, "
                                            "0.1875]}"}));
  const Grid r(PETSC_COMM_SELF, hole.mesh);
  const BoundaryCondition& north = boundary(hole.flow.boundaries, Side::north);
  EXPECT_DOUBLE_EQ(open_share(north, r, Side::north, 1, 7, 0),
                   (0.1875 * 0.1875 - 0.125 * 0.125) / (0.25 * 0.25 - 0.125 * 0.125));
  EXPECT_EQ(open_share(north, r, Side::north, 0, 7, 0), 1.0);
  // A ghost beyond an end of the side takes the share of the side's cell beside it.
  EXPECT_EQ(open_share(north, r, Side::north, -1, 8, 0), 1.0);
  EXPECT_EQ(open_share(north, r, Side::north, 8, 8, 0), 0.0);
  EXPECT_EQ(open_share(west, g, Side::west, -1, 8, 0), 0.0);
}

TEST(CaseFile, AnInletRefusesWhatItCannotBe) {
  const std::vector<std::string> open_east{"soil.rheology.friction_angle=30", "boundary.east={type = \"atmosphere\"}"};
  auto error_with = [&](const std::string& west, std::vector<std::string> more = {}) {
    auto o = open_east;
    o.push_back("boundary.west=" + west);
    o.insert(o.end(), more.begin(), more.end());
    return error_of(two_phase, o);
  };
  const std::string outward = error_with("{type = \"inlet\", velocity = [-0.5, 0.0]}");
  EXPECT_NE(outward.find("boundary.west.velocity: an inlet's velocity must point into the domain (its x component "
                         "greater than 0)"), std::string::npos) << outward;
  const std::string along = error_with("{type = \"inlet\", velocity = [0.0, 0.3]}");
  EXPECT_NE(along.find("must point into the domain"), std::string::npos) << along;
  const std::string missing = error_with("{type = \"inlet\", soil_fraction = 1.0}");
  EXPECT_NE(missing.find("boundary.west.velocity: missing"), std::string::npos) << missing;
  const std::string fraction = error_with("{type = \"inlet\", velocity = [1.0, 0.0], soil_fraction = 1.5}");
  EXPECT_NE(fraction.find("boundary.west.soil_fraction: 1.5 is invalid"), std::string::npos) << fraction;
  const std::string depth = error_with("{type = \"inlet\", velocity = [1.0, 0.0], soil_depth = -0.1}");
  EXPECT_NE(depth.find("boundary.west.soil_depth: -0.1 is invalid, must be positive"), std::string::npos) << depth;
  const std::string material = error_with("{type = \"inlet\", velocity = [1.0, 0.0], material = \"clay\"}");
  EXPECT_NE(material.find("boundary.west.material: no soil material named 'clay'"), std::string::npos) << material;
  const std::string closed = error_with("{type = \"inlet\", velocity = [1.0, 0.0]}",
                                        {"boundary.east={type = \"wall\"}", "boundary.north={type = \"wall\"}"});
  EXPECT_NE(closed.find("boundary: an inlet needs an open side"), std::string::npos) << closed;
  const std::string bottom = error_with("{type = \"wall\"}", {"boundary.south={type = \"inlet\", velocity = [0.0, "
                                                                 "1.0], soil_depth = 0.1}"});
  EXPECT_NE(bottom.find("boundary.south.soil_depth: the depth is measured up from the bottom"), std::string::npos)
      << bottom;
  const std::string normal = error_with("{type = \"inlet\", velocity = [1.0, 0.0], span_x = [0.0, 0.5]}");
  EXPECT_NE(normal.find("boundary.west.span_x: the west side lies across x; its opening is given along the side "
                        "(span_y)"), std::string::npos) << normal;
  const std::string reversed = error_with("{type = \"inlet\", velocity = [1.0, 0.0], span_y = [0.5, 0.2]}");
  EXPECT_NE(reversed.find("boundary.west.span_y: [0.5, 0.2]; the opening runs from its low end"), std::string::npos)
      << reversed;
  const std::string beyond = error_with("{type = \"inlet\", velocity = [1.0, 0.0], span_y = [1.5, 2.0]}");
  EXPECT_NE(beyond.find("boundary.west.span_y: [1.5, 2] lies outside the side, which runs from 0 to 1 along y"),
            std::string::npos) << beyond;
  const std::string airy = error_with(
      "{type = \"inlet\", velocity = [1.0, 0.0], soil_fraction = 1.0, soil_depth = 0.2, span_y = [0.25, 0.5]}");
  EXPECT_NE(airy.find("boundary.west.span_y: the opening starts at y = 0.25, above the soil's depth (up to y = 0.2)"),
            std::string::npos) << airy;
  const std::string planar = error_with("{type = \"inlet\", velocity = [1.0, 0.0], span_z = [0.0, 0.5]}");
  EXPECT_NE(planar.find("boundary.west.span_z: a planar mesh has no z"), std::string::npos) << planar;
  const std::string stray = error_with("{type = \"inlet\", velocity = [1.0, 0.0], pressure = 3.0}");
  EXPECT_NE(stray.find("boundary.west.pressure"), std::string::npos) << stray;
  // One phase: the soil keys belong to cases with soil.
  const std::string one_phase =
      error_of(minimal, {"boundary.west={type = \"inlet\", velocity = [1.0, 0.0], soil_fraction = 1.0}",
                         "boundary.east={type = \"atmosphere\"}"});
  EXPECT_NE(one_phase.find("boundary.west.soil_fraction: applies to cases with soil only"), std::string::npos)
      << one_phase;
  for (const char* key : {"material = \"clay\"", "soil_fraction = 1.5"}) {  // named before their values are read
    const std::string west = "boundary.west={type = \"inlet\", velocity = [1.0, 0.0], " + std::string(key) + "}";
    const std::string e = error_of(minimal, {west, "boundary.east={type = \"atmosphere\"}"});
    EXPECT_NE(e.find("applies to cases with soil only (this case has [fluid], no [soil])"), std::string::npos) << e;
  }
  EXPECT_NO_THROW(parse_case(minimal, {"boundary.west={type = \"inlet\", velocity = [1.0, 0.0]}",
                                       "boundary.east={type = \"atmosphere\"}"}));
}

TEST(CaseFile, RheologyParametersAreValidated) {
  const std::string e = error_of(two_phase);
  EXPECT_NE(e.find("soil.rheology"), std::string::npos) << e;
  EXPECT_NE(e.find("friction_angle"), std::string::npos) << e;
  const std::string model = error_of(two_phase, {"soil.rheology.friction_angle=30", "soil.rheology.model=coulomb"});
  EXPECT_NE(model.find("soil.rheology.model"), std::string::npos) << model;
  EXPECT_NO_THROW(parse_case(two_phase, {"soil.rheology.friction_angle=30"}));
  // The strain rate on faces belongs to the face viscosities, which only yield_pressure = face builds.
  const std::string rate =
      error_of(two_phase, {"soil.rheology.friction_angle=30", "soil.yield_pressure=cell", "soil.strain_rate=face"});
  EXPECT_NE(rate.find("soil.strain_rate"), std::string::npos) << rate;
  EXPECT_NE(rate.find("yield_pressure"), std::string::npos) << rate;
  EXPECT_NO_THROW(parse_case(two_phase, {"soil.rheology.friction_angle=30", "soil.strain_rate=face", "soil.yield_pressure=face"}));
  // The face's own soil fraction needs the one evaluation on the face, which strain_rate = face makes.
  const std::string fraction = error_of(two_phase, {"soil.rheology.friction_angle=30", "soil.yield_pressure=face",
                                                    "soil.strain_rate=cell", "soil.face_fraction=face"});
  EXPECT_NE(fraction.find("soil.face_fraction"), std::string::npos) << fraction;
  EXPECT_NE(fraction.find("strain_rate"), std::string::npos) << fraction;
  EXPECT_NO_THROW(parse_case(two_phase, {"soil.rheology.friction_angle=30", "soil.strain_rate=face",
                                         "soil.yield_pressure=face", "soil.face_fraction=face"}));
}

// Soil materials: each names a strength of the rheology's model; a shape's `material` must name one,
// and each must be some shape's.
TEST(CaseFile, SoilMaterialsAreNamedValidatedAndUsed) {
  const std::string phi = "soil.rheology.friction_angle=30";
  const std::string clay = "soil.materials=[{name = \"clay\", friction_angle = 0.0, cohesion = 2e4}]";
  const std::string shapes = "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [1, 0.2], material = \"clay\"}, "
                             "{shape = \"box\", lower = [0, 0.2], upper = [0.5, 0.5]}]";
  const CaseConfig c = parse_case(two_phase, {phi, clay, shapes});
  ASSERT_EQ(c.soil->materials.size(), 1u);
  EXPECT_EQ(c.soil->materials[0].name, "clay");
  EXPECT_EQ(c.soil->materials[0].rheology.cohesion, 2e4);
  EXPECT_EQ(c.soil->initial_material, (std::vector<int>{1, 0}));
  // A material's density is the soil's unless given; given, it must be positive.
  EXPECT_EQ(c.soil->materials[0].rheology.density, c.soil->soil_density);
  EXPECT_FALSE(c.soil->materials_differ_in_density());
  const CaseConfig heavy = parse_case(two_phase, {phi, "soil.materials=[{name = \"clay\", density = 1800.0}]", shapes});
  EXPECT_EQ(heavy.soil->materials[0].rheology.density, 1800.0);
  EXPECT_TRUE(heavy.soil->materials_differ_in_density());
  const std::string density = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\", density = -1800.0}]", shapes});
  EXPECT_NE(density.find("soil.materials[0].density"), std::string::npos) << density;
  EXPECT_NE(density.find("positive"), std::string::npos) << density;
  // A material's yield surface and cohesion are the rheology's unless given; a material whose friction
  // is mu(I), which takes no cohesion, does not inherit the rheology's, and refuses one given.
  EXPECT_EQ(c.soil->materials[0].rheology.model, c.soil->rheology->model);
  const std::string cohesive = "soil.rheology.cohesion=5000";
  const CaseConfig mc = parse_case(two_phase, {phi, cohesive, "soil.materials=[{name = \"clay\", model = \"mohr_coulomb\"}]", shapes});
  EXPECT_EQ(mc.soil->materials[0].rheology.model, rheology::Model::mohr_coulomb);
  EXPECT_EQ(mc.soil->materials[0].rheology.cohesion, 5000.0);
  EXPECT_EQ(mc.soil->materials[0].rheology.friction_angle_deg, 30.0);
  const CaseConfig dpb = parse_case(two_phase, {phi, cohesive, "soil.materials=[{name = \"clay\", friction_angle = 25.0}]", shapes});
  EXPECT_EQ(dpb.soil->materials[0].rheology.cohesion, 5000.0);
  const CaseConfig sand_of_grains = parse_case(two_phase, {phi, cohesive, "soil.materials=[{name = \"clay\", model = \"drucker_prager\", friction = \"mu_of_I\"}]", shapes});
  EXPECT_EQ(sand_of_grains.soil->materials[0].rheology.cohesion, 0.0);
  const std::string grains_cohesion = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\", model = \"mohr_coulomb\", friction = \"mu_of_I\", cohesion = 1e3}]", shapes});
  EXPECT_NE(grains_cohesion.find("soil.materials[0]"), std::string::npos) << grains_cohesion;
  EXPECT_NE(grains_cohesion.find("cohesion"), std::string::npos) << grains_cohesion;
  EXPECT_NE(grains_cohesion.find("friction = \"constant\""), std::string::npos) << grains_cohesion;
  const std::string model = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\", model = \"cam_clay\"}]", shapes});
  EXPECT_NE(model.find("soil.materials[0].model: 'cam_clay' is not one of"), std::string::npos) << model;
  // A key the material does not have; no strength at all (phi = 0 without cohesion); a name twice.
  const std::string viscosity = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\", viscosity = 1.0}]", shapes});
  EXPECT_NE(viscosity.find("soil.materials[0].viscosity"), std::string::npos) << viscosity;
  const std::string weak = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\", friction_angle = 0.0}]", shapes});
  EXPECT_NE(weak.find("soil.materials[0]"), std::string::npos) << weak;
  EXPECT_NE(weak.find("friction_angle"), std::string::npos) << weak;
  const std::string twice = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\"}, {name = \"clay\"}]", shapes});
  EXPECT_NE(twice.find("soil.materials[1].name"), std::string::npos) << twice;
  const std::string odd = error_of(two_phase, {phi, "soil.materials=[{name = \"wet clay\"}]", shapes});
  EXPECT_NE(odd.find("not a plain name"), std::string::npos) << odd;
  // A shape of a material the case does not have, a material of no shape.
  const std::string missing = error_of(two_phase, {phi, clay, "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [1, 0.2], material = \"sand\"}]"});
  EXPECT_NE(missing.find("initial.soil[0].material"), std::string::npos) << missing;
  EXPECT_NE(missing.find("'sand'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("clay"), std::string::npos) << missing;
  const std::string unused = error_of(two_phase, {phi, clay});
  EXPECT_NE(unused.find("soil.materials[0]"), std::string::npos) << unused;
  EXPECT_NE(unused.find("no initial.soil shape"), std::string::npos) << unused;
  // A material's friction law is its own: a clay of constant friction beside a mu(I) sand gives its
  // angle; a mu(I) material takes the rheology's constants unless given. The regularisation is shared.
  const std::string sand = "soil.rheology={model = \"drucker_prager\", friction = \"mu_of_I\", mu_s = 0.4}";
  const CaseConfig beside = parse_case(two_phase, {sand, "soil.materials=[{name = \"clay\", model = \"drucker_prager_bingham\", "
                                                         "friction = \"constant\", friction_angle = 0.0, cohesion = 2e4}]", shapes});
  EXPECT_EQ(beside.soil->materials[0].rheology.friction, rheology::FrictionSource::constant);
  EXPECT_EQ(beside.soil->materials[0].rheology.cohesion, 2e4);
  const std::string angle = error_of(two_phase, {sand, "soil.materials=[{name = \"clay\", friction = \"constant\"}]", shapes});
  EXPECT_NE(angle.find("soil.materials[0].friction_angle: required"), std::string::npos) << angle;
  const CaseConfig grains = parse_case(two_phase, {"soil.rheology.friction_angle=0", "soil.rheology.cohesion=2e4",
                                                   "soil.materials=[{name = \"clay\", model = \"drucker_prager\", "
                                                   "friction = \"mu_of_I\", mu_2 = 0.7}]", shapes});
  EXPECT_EQ(grains.soil->materials[0].rheology.friction, rheology::FrictionSource::mu_of_I);
  EXPECT_EQ(grains.soil->materials[0].rheology.limiting_friction, 0.7);
  EXPECT_EQ(grains.soil->materials[0].rheology.static_friction, rheology::RheologyParameters{}.static_friction);
  const std::string shared = error_of(two_phase, {phi, "soil.materials=[{name = \"clay\", m = 10.0}]", shapes});
  EXPECT_NE(shared.find("soil.materials[0].m: the soils share the regularisation"), std::string::npos) << shared;
  const std::string empty = error_of(two_phase, {phi, clay, "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [1, 0.2], material = \"\"}]"});
  EXPECT_NE(empty.find("initial.soil[0].material: empty"), std::string::npos) << empty;
  const std::string no_materials = error_of(two_phase, {phi, shapes});
  EXPECT_NE(no_materials.find("the case has no [[soil.materials]]"), std::string::npos) << no_materials;
}

// A polygon's outline from a file (points_file), relative to the case file's directory: comment lines
// and a header skipped, commas or blanks between x and y; the case as run holds the points. A file
// that is missing, a line that is not two numbers (named by its line, an empty field among them, its
// bytes shown printable), both keys, or a shape other than a polygon is refused.
TEST(CaseFile, PolygonPointsFromAFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("granflow_points_" + std::to_string(::getpid()));
  fs::create_directories(dir / "terrain");
  {
    std::ofstream(dir / "terrain" / "ground.csv") << "# surveyed ground, m\nx,y\n-1, -1\n2 -1\n\n2,0.3\n-1,0.1\n";
    std::ofstream(dir / "terrain" / "bad.csv") << "x,y\n0,0\n1,0\n1,zero\n";
    // A spreadsheet's export: a byte-order mark, CRLF line ends, semicolons.
    std::ofstream(dir / "terrain" / "exported.csv") << "\xEF\xBB\xBF-1;-1\r\n2;-1\r\n2;0.3\r\n-1;0.1\r\n";
    std::ofstream(dir / "terrain" / "typo.csv") << "-1,-1x\n2,-1\n2,0.3\n-1,0.1\n";  // a first line with a typo is no header
    std::ofstream(dir / "terrain" / "two.csv") << "x,y\n0,0\n1,0\n";
    std::ofstream(dir / "terrain" / "far.csv") << "0,0\n1e100,0\n0.2,0.1\n";  // as points = [...] would be refused
    // A column left empty would shift the numbers after it: "0.2,,0" is not the point (0.2, 0).
    std::ofstream(dir / "terrain" / "gap.csv") << "-1,-1\n2,-1\n0.2 ,, 0\n-1,0.1\n";
    std::ofstream(dir / "terrain" / "trailing.csv") << "-1,-1,\n2,-1,\n2,0.3,\n";
    std::ofstream(dir / "terrain" / "leading.csv") << "x,y\n;-1;-1\n";
    std::ofstream(dir / "terrain" / "binary.csv") << "x,y\n\x7F" "ELF\x02\x01\x01" + std::string(200, 'a') + "\n";
  }
  const fs::path source = dir / "case.toml";
  auto obstacle = [](const std::string& keys) { return "obstacle=[{shape = \"polygon\", " + keys + "}]"; };
  const std::string phi = "soil.rheology.friction_angle=30", coupled = "numerics.pressure_coupling=coupled";
  const CaseConfig c = parse_case(two_phase, {phi, coupled, obstacle("points_file = \"terrain/ground.csv\"")}, source);
  ASSERT_EQ(c.obstacles.size(), 1u);
  const auto& v = std::get<interface::Polygon>(c.obstacles[0]).vertices;
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0], (std::array<double, 2>{-1.0, -1.0}));
  EXPECT_EQ(v[1], (std::array<double, 2>{2.0, -1.0}));
  EXPECT_EQ(v[2], (std::array<double, 2>{2.0, 0.3}));
  EXPECT_EQ(v[3], (std::array<double, 2>{-1.0, 0.1}));
  EXPECT_NE(c.as_run.find("points = [ [ -1.0, -1.0 ]"), std::string::npos) << c.as_run;
  EXPECT_EQ(c.as_run.find("points_file"), std::string::npos) << c.as_run;
  // The same file as an initial soil shape, by an absolute path.
  const std::string soil = "initial.soil=[{shape = \"polygon\", points_file = \"" + (dir / "terrain" / "ground.csv").string() + "\"}]";
  EXPECT_EQ(std::get<interface::Polygon>(parse_case(two_phase, {phi, soil}).soil->initial_soil[0]).vertices, v);
  auto error = [&](const std::string& override) { return error_of(two_phase, {phi, coupled, override}, source); };
  EXPECT_EQ(std::get<interface::Polygon>(
                parse_case(two_phase, {phi, coupled, obstacle("points_file = \"terrain/exported.csv\"")}, source).obstacles[0])
                .vertices,
            v);
  const std::string typo = error(obstacle("points_file = \"terrain/typo.csv\""));
  EXPECT_NE(typo.find("typo.csv:1: expected two numbers, x and y in m, found '-1,-1x'"), std::string::npos) << typo;
  const std::string two = error(obstacle("points_file = \"terrain/two.csv\""));
  EXPECT_NE(two.find("obstacle[0].points_file ('"), std::string::npos) << two;
  EXPECT_NE(two.find("two.csv'): the polygon needs at least 3 distinct points"), std::string::npos) << two;
  const std::string far = error(obstacle("points_file = \"terrain/far.csv\""));
  EXPECT_NE(far.find("obstacle[0].points_file: "), std::string::npos) << far;
  EXPECT_NE(far.find("far.csv:2: 1e+100 is beyond the magnitudes granflow computes with"), std::string::npos) << far;
  const std::string missing = error(obstacle("points_file = \"terrain/none.csv\""));
  EXPECT_NE(missing.find("obstacle[0].points_file: cannot open"), std::string::npos) << missing;
  EXPECT_NE(missing.find("none.csv"), std::string::npos) << missing;
  const std::string bad = error(obstacle("points_file = \"terrain/bad.csv\""));
  EXPECT_NE(bad.find("bad.csv:4: expected two numbers"), std::string::npos) << bad;
  const std::string gap = error(obstacle("points_file = \"terrain/gap.csv\""));
  EXPECT_NE(gap.find("gap.csv:3: expected two numbers, x and y in m, found '0.2 ,, 0'"), std::string::npos) << gap;
  const std::string trailing = error(obstacle("points_file = \"terrain/trailing.csv\""));
  EXPECT_NE(trailing.find("trailing.csv:1: expected two numbers"), std::string::npos) << trailing;
  const std::string leading = error(obstacle("points_file = \"terrain/leading.csv\""));
  EXPECT_NE(leading.find("leading.csv:2: expected two numbers"), std::string::npos) << leading;
  const std::string binary = error(obstacle("points_file = \"terrain/binary.csv\""));
  EXPECT_NE(binary.find("binary.csv:2: expected two numbers, x and y in m, found '\\x7FELF\\x02\\x01\\x01aaa"),
            std::string::npos)
      << binary;
  EXPECT_NE(binary.find("aaa... (207 bytes)'"), std::string::npos) << binary;
  EXPECT_LT(binary.size(), 400u) << binary;
  const std::string both = error(obstacle("points_file = \"terrain/ground.csv\", points = [[0, 0], [1, 0], [1, 1]]"));
  EXPECT_NE(both.find("not both"), std::string::npos) << both;
  const std::string box = error("obstacle=[{shape = \"box\", points_file = \"terrain/ground.csv\"}]");
  EXPECT_NE(box.find("obstacle[0].points_file: used only with shape = \"polygon\""), std::string::npos) << box;
  fs::remove_all(dir);
}

// A rheology constant that the chosen model, friction or regularisation does not read is refused,
// naming the key and what reads it; the same key is accepted where it is read.
TEST(CaseFile, RheologyConstantsTheModelDoesNotReadAreRefused) {
  const std::vector<std::string> valid{"soil.rheology.friction_angle=30"};
  auto with = [&](std::initializer_list<std::string> extra) {
    std::vector<std::string> o = valid;
    o.insert(o.end(), extra);
    return o;
  };
  struct Refused {
    std::string set, key, reader;
  };
  for (const Refused& r : {Refused{"soil.rheology.mu_2=0.6", "soil.rheology.mu_2", "friction = \"mu_of_I\""},
                           Refused{"soil.rheology.grain_diameter=1e-3", "soil.rheology.grain_diameter", "mu_of_I"},
                           Refused{"soil.rheology.nu_max=1", "soil.rheology.nu_max", "regularisation = \"clip\""},
                           Refused{"soil.rheology.friction=mu_of_I", "soil.rheology.friction_angle",
                                   "friction = \"constant\""},
                           Refused{"soil.rheology.matsuoka_nakai_fit=triaxial", "soil.rheology.matsuoka_nakai_fit",
                                   "model = \"matsuoka_nakai\""}}) {
    const std::string e = error_of(two_phase, with({r.set}));
    EXPECT_NE(e.find(r.key + ": used only with"), std::string::npos) << r.set << ": " << e;
    EXPECT_NE(e.find(r.reader), std::string::npos) << r.set << ": " << e;
  }
  const std::string clip = error_of(two_phase, with({"soil.rheology.regularisation=clip", "soil.rheology.mu_min=1e-3"}));
  EXPECT_NE(clip.find("soil.rheology.mu_min: used only with regularisation = \"exponential\""), std::string::npos) << clip;
  EXPECT_NO_THROW(parse_case(two_phase, {"soil.rheology={model = \"drucker_prager\", friction = \"mu_of_I\", "
                                         "mu_2 = 0.6, grain_diameter = 1e-3}"}));
  EXPECT_NO_THROW(parse_case(two_phase, with({"soil.rheology.regularisation=clip", "soil.rheology.nu_max=1"})));
  EXPECT_NO_THROW(parse_case(two_phase, with({"soil.rheology.model=matsuoka_nakai",
                                              "soil.rheology.matsuoka_nakai_fit=triaxial"})));
  EXPECT_NO_THROW(parse_case(two_phase, with({"soil.rheology.m=1e4", "soil.rheology.mu_min=1e-2"})));
}

// The message states the rule that was broken.
TEST(CaseFile, MessagesStateTheRuleBroken) {
  EXPECT_NE(error_of(minimal, {"mesh.upper=[1.0, nan]"}).find("finite"), std::string::npos);
  EXPECT_NE(error_of(minimal, {"mesh.cells=[100000001, 1]"}).find("more than 1e8"), std::string::npos);
  // An integer beyond what a double holds exactly is still the number it says.
  EXPECT_NE(error_of(minimal, {"mesh.cells=[9223372036854775807, 1]"}).find("more than 1e8"), std::string::npos);
  // A step below a nanosecond fails in the solve (V / a_P underflows), so it is refused here.
  for (const char* key : {"time.end=1e-20", "time.dt=1e-12", "time.max_dt=0", "time.end=-1"}) {
    const std::string e = error_of(minimal, {key});
    EXPECT_NE(e.find(std::string(key).substr(0, std::string(key).find('='))), std::string::npos) << key << ": " << e;
    EXPECT_NE(e.find("at least 1e-9 s"), std::string::npos) << key << ": " << e;
  }
  EXPECT_NO_THROW(parse_case(minimal, {"time.end=1e-9"}));
  // As many outputs as output.interval may ask for, and no more, in a list of times.
  std::string times = "output.times=[0.0";
  for (int k = 1; k <= 100000; ++k) times += ", 0.5";
  EXPECT_NE(error_of(minimal, {times + "]"}).find("output.times: 100001 times, more than 1e+05 outputs"), std::string::npos);
  EXPECT_NE(error_of(two_phase, {"soil.rheology.friction_angle=30", "mixture.density=\"arctan\"", "mixture.arctan_N=2e6"}).find("[1e-06, 1000000]"),
            std::string::npos)
      << error_of(two_phase, {"soil.rheology.friction_angle=30", "mixture.density=\"arctan\"", "mixture.arctan_N=2e6"});
}

TEST(CaseFile, InterfaceSubstepsMustBeAPositiveWholeNumber) {
  const std::vector<std::string> soil{"soil.rheology.friction_angle=30", "time.interface_substeps=3"};
  EXPECT_EQ(parse_case(two_phase, soil).time.interface_substeps, 3);
  EXPECT_EQ(parse_case(minimal).time.interface_substeps, 1);
  for (const char* bad : {"time.interface_substeps=0", "time.interface_substeps=1.5"}) {
    const std::string e = error_of(two_phase, {"soil.rheology.friction_angle=30", bad});
    EXPECT_NE(e.find("time.interface_substeps"), std::string::npos) << bad << ": " << e;
  }
}

// An integer key takes a whole number written as a float (1e5), as mesh.cells does; not 1.5 or 1e300.
TEST(CaseFile, IntegersMayBeWrittenAsWholeFloats) {
  EXPECT_EQ(parse_case(minimal, {"time.max_steps=1e5"}).time.max_steps, 100000);
  EXPECT_EQ(parse_case(minimal, {"solver.pressure.max_iterations=250.0"}).flow.pressure_solver.max_iterations, 250);
  for (const char* bad : {"time.max_steps=1.5", "time.max_steps=1e300", "time.max_steps=nan"}) {
    const std::string e = error_of(minimal, {bad});
    EXPECT_NE(e.find("time.max_steps: expected an integer (a whole number)"), std::string::npos) << bad << ": " << e;
  }
}

// A relative tolerance of 1 is refused as PETSc refuses it, naming the key, not by PETSc at the solver's set-up.
TEST(CaseFile, RelativeToleranceBelowOne) {
  EXPECT_EQ(error_of(minimal, {"solver.pressure.rtol=1"}), "solver.pressure.rtol: 1 is invalid, must be in [0, 1)");
  EXPECT_EQ(error_of(minimal, {"solver.pressure.rtol=0.999"}), "");
}

// Keys that only a case with soil reads are refused in a single-phase case, not ignored.
TEST(CaseFile, TwoPhaseKeysRefusedWithoutSoil) {
  for (const char* key : {"time.interface_substeps=3", "time.interface_courant=0.3", "time.courant_region=\"soil\"",
                          "boundary.north={type = \"atmosphere\", inflow_soil_fraction = 0.5}"}) {
    const std::string e = error_of(minimal, {key});
    EXPECT_NE(e.find("applies to cases with soil only"), std::string::npos) << key << ": " << e;
  }
  EXPECT_EQ(error_of(two_phase, {"soil.rheology.friction_angle=30", "time.interface_substeps=3"}), "");
  // So are the tables only such a case reads, named as such rather than as unknown keys.
  for (const char* table : {"mixture.density=\"arctan\"", "air.density=1.0", "initial.soil=[]"}) {
    const std::string e = error_of(minimal, {table});
    EXPECT_NE(e.find(": applies to cases with soil only (this case has no [soil], and [fluid] for its one phase)"),
              std::string::npos) << table << ": " << e;
  }
  // A light phase written as [fluid] beside [soil] is named first, not the [air] it lacks.
  std::string fluid_for_air = two_phase;
  fluid_for_air.replace(fluid_for_air.find("[air]"), 5, "[fluid]");
  const std::string e = error_of(fluid_for_air);
  EXPECT_NE(e.find("fluid: a two-phase case ([soil] and [air]) takes no [fluid] table (the light phase is [air])"),
            std::string::npos) << e;
}

// A wall of its own friction: the angle and adhesion checked, and the soil it acts on granular with its
// viscosity taken on faces.
// Periodic sides join west and east: both or neither, a planar mesh of one cell width along x, no air
// band; the air's weight along the slope is then carried by a mean pressure gradient.
TEST(CaseFile, PeriodicSidesComeInTheWestEastPair) {
  const std::vector<std::string> joined = {"soil.rheology.friction_angle=30", "boundary.west={type = \"periodic\"}",
                                           "boundary.east={type = \"periodic\"}"};
  auto with = [&](std::vector<std::string> keys) {
    keys.insert(keys.begin(), joined.begin(), joined.end());
    return keys;
  };
  const CaseConfig c = parse_case(two_phase, with({}));
  EXPECT_TRUE(c.mesh.periodic_x);
  EXPECT_EQ(c.flow.boundaries[int(Side::west)].kind, BoundaryKind::periodic);
  EXPECT_EQ(c.flow.periodic_ambient_density, 1.0);  // the air's
  const CaseConfig walls = parse_case(two_phase, {"soil.rheology.friction_angle=30"});
  EXPECT_FALSE(walls.mesh.periodic_x);
  EXPECT_EQ(walls.flow.periodic_ambient_density, 0.0);
  const CaseConfig fluid = parse_case(minimal, {"boundary.west={type = \"periodic\"}", "boundary.east={type = \"periodic\"}"});
  EXPECT_TRUE(fluid.mesh.periodic_x);
  EXPECT_EQ(fluid.flow.periodic_ambient_density, 0.0);  // a single fluid: the slope drives it
  struct Bad {
    std::vector<std::string> keys;
    const char* names;
  };
  for (const Bad& b :
       {Bad{{"soil.rheology.friction_angle=30", "boundary.west={type = \"periodic\"}"},
            "boundary.west.type: a periodic side needs the opposite side periodic too (boundary.east = { type = \"periodic\" })"},
        Bad{{"soil.rheology.friction_angle=30", "boundary.east={type = \"periodic\"}"}, "boundary.east.type: a periodic side"},
        Bad{with({"boundary.north={type = \"periodic\"}"}), "boundary.north.type: only the west and east sides can be periodic"},
        Bad{with({"mesh.grading=[2.0, 1.0]"}), "mesh.grading: periodic west and east sides need cells of one width along x"},
        Bad{with({"mesh.cells=[2, 8]"}), "mesh.cells: periodic west and east sides need at least 3 cells along x, got 2"},
        Bad{with({"numerics.pressure_coupling=\"coupled\"", "numerics.air_band=4"}),
            "numerics.air_band: the air band's region does not reach across periodic sides"}}) {
    const std::string e = error_of(two_phase, b.keys);
    EXPECT_NE(e.find(b.names), std::string::npos) << b.keys.back() << ": " << e;
  }
  const std::string axis =
      error_of(two_phase, with({"mesh.geometry=\"axisymmetric\"", "mesh.lower=[0.25, 0.0]", "mesh.upper=[1.25, 1.0]"}));
  EXPECT_NE(axis.find("periodic"), std::string::npos) << axis;
}

TEST(CaseFile, WallFrictionIsValidatedAndNeedsAGranularSoilOnFaces) {
  const std::vector<std::string> granular = {"soil.rheology.friction_angle=30", "soil.yield_pressure=face"};
  auto with = [&](std::vector<std::string> keys) {
    keys.insert(keys.begin(), granular.begin(), granular.end());
    return keys;
  };
  const CaseConfig c = parse_case(two_phase, with({"boundary.south={type = \"wall\", friction_angle = 12.0}",
                                                   "boundary.west={type = \"wall\", adhesion = 50.0}"}));
  const auto& south = c.flow.boundaries[int(Side::south)].friction;
  ASSERT_TRUE(south);
  EXPECT_NEAR(south->friction_coefficient, std::tan(12.0 * std::numbers::pi / 180.0), 1e-15);
  EXPECT_EQ(south->adhesion, 0.0);
  EXPECT_EQ(c.flow.boundaries[int(Side::west)].friction->friction_coefficient, 0.0);
  EXPECT_EQ(c.flow.boundaries[int(Side::west)].friction->adhesion, 50.0);
  EXPECT_FALSE(c.flow.boundaries[int(Side::east)].friction);
  // The wall's strength at its pressure: a + tan(delta) p, nothing at a pressure below zero.
  EXPECT_NEAR(south->shear_strength(1000.0), 1000.0 * std::tan(12.0 * std::numbers::pi / 180.0), 1e-12);
  EXPECT_EQ(south->shear_strength(-1000.0), 0.0);
  EXPECT_EQ(c.flow.boundaries[int(Side::west)].friction->shear_strength(-1.0), 50.0);
  struct Bad {
    std::vector<std::string> keys;
    const char* names;
  };
  for (const Bad& b : {Bad{with({"boundary.south={type = \"wall\", friction_angle = 90.0}"}), "boundary.south.friction_angle: 90 is outside (0, 90)"},
                       Bad{with({"boundary.south={type = \"wall\", friction_angle = 0.0}"}), "a wall without friction is type = \"slip\""},
                       Bad{with({"boundary.south={type = \"wall\", friction_angle = -5.0, adhesion = 10.0}"}), "boundary.south.friction_angle: -5"},
                       Bad{with({"boundary.south={type = \"wall\", adhesion = -1.0}"}), "boundary.south.adhesion"},
                       Bad{with({"boundary.south={type = \"wall\", adhesion = 0.0}"}),
                           "boundary.south.adhesion: 0 without a friction_angle leaves the wall no strength"},
                       Bad{with({"boundary.north={type = \"atmosphere\", friction_angle = 10.0}"}), "boundary.north.friction_angle"},
                       Bad{with({"boundary.east={type = \"slip\", friction_angle = 10.0}"}), "boundary.east.friction_angle"},
                       Bad{{"soil.rheology.friction_angle=30", "soil.yield_pressure=cell", "boundary.south={type = \"wall\", friction_angle = 10.0}"},
                           "boundary.south: a wall's friction (friction_angle, adhesion) needs soil.yield_pressure = \"face\""},
                       // a misspelt friction key: the known keys name the wall's friction keys too
                       Bad{with({"boundary.south={type = \"wall\", frction_angle = 15.0}"}),
                           "boundary.south.frction_angle: unknown key (known keys here: adhesion, friction_angle, type, velocity)"}}) {
    const std::string e = error_of(two_phase, b.keys);
    EXPECT_NE(e.find(b.names), std::string::npos) << b.keys.back() << ": " << e;
  }
  // An obstacle of its own friction, checked alike; the others hold the soil by its own strength.
  const char* box = "{shape = \"box\", lower = [0.6, 0.0], upper = [1.0, 0.3]}";
  auto obstacles = [&](const std::string& keys) {
    return fmt::format("obstacle=[{}, {{shape = \"box\", lower = [0.8, 0.5], upper = [1.0, 1.0]{}}}]", box, keys);
  };
  const CaseConfig o = parse_case(two_phase, with({"numerics.pressure_coupling=coupled", obstacles(", friction_angle = 15.0")}));
  ASSERT_EQ(o.obstacle_friction.size(), 2u);
  EXPECT_FALSE(o.obstacle_friction[0]);
  ASSERT_TRUE(o.obstacle_friction[1]);
  EXPECT_NEAR(o.obstacle_friction[1]->friction_coefficient, std::tan(15.0 * std::numbers::pi / 180.0), 1e-15);
  const std::string steep = error_of(two_phase, with({"numerics.pressure_coupling=coupled", obstacles(", friction_angle = 95.0")}));
  EXPECT_NE(steep.find("obstacle[1].friction_angle: 95 is outside (0, 90)"), std::string::npos) << steep;
  const std::string cells = error_of(two_phase, {"soil.rheology.friction_angle=30", "numerics.pressure_coupling=coupled",
                                                 "soil.yield_pressure=cell", obstacles(", adhesion = 10.0")});
  EXPECT_NE(cells.find("obstacle[1]: a wall's friction (friction_angle, adhesion) needs soil.yield_pressure = \"face\""),
            std::string::npos) << cells;
  // Soil only, and granular soil.
  const std::string fluid = error_of(minimal, {"boundary.south={type = \"wall\", friction_angle = 10.0}"});
  EXPECT_NE(fluid.find("boundary.south.friction_angle: applies to cases with soil only"), std::string::npos) << fluid;
  std::string newtonian(two_phase);
  newtonian.erase(newtonian.find("[soil.rheology]"), std::string("[soil.rheology]\nmodel = \"drucker_prager_bingham\"\nfriction_angle = 95.0\n").size());
  const std::string e = error_of(newtonian, {"soil.viscosity=1.0", "boundary.south={type = \"wall\", friction_angle = 10.0}"});
  EXPECT_NE(e.find("boundary.south: a wall's friction (friction_angle, adhesion) acts on a granular soil"), std::string::npos) << e;
}

// A granular soil takes the numerics a pile next to air needs by default: the viscosity on the faces,
// the coupled solve over the soil and an air band wide enough for the step's sweeps where one may be
// laid; a Newtonian soil keeps the projection and the cells' evaluations.
TEST(CaseFile, GranularSoilDefaultsToTheFaceViscosityAndTheCoupledSolveOverAnAirBand) {
  const CaseConfig granular = parse_case(two_phase, {"soil.rheology.friction_angle=30"});
  EXPECT_EQ(granular.flow.numerics.pressure_coupling, PressureCoupling::coupled);
  EXPECT_EQ(granular.flow.numerics.air_band, 12);
  EXPECT_TRUE(granular.flow.numerics.conservative_momentum);
  EXPECT_EQ(granular.soil->yield_pressure, YieldPressure::face);
  EXPECT_EQ(granular.soil->strain_rate, StrainRateAt::face);
  EXPECT_EQ(granular.soil->face_fraction, FaceFraction::face);
  // Each evaluation defaults to the one before it.
  const CaseConfig cells = parse_case(two_phase, {"soil.rheology.friction_angle=30", "soil.yield_pressure=cell"});
  EXPECT_EQ(cells.soil->strain_rate, StrainRateAt::cell);
  EXPECT_EQ(cells.soil->face_fraction, FaceFraction::cells);
  // The band is wide enough for the sweeps (2 S + 1), and none where it may not be laid.
  EXPECT_EQ(parse_case(two_phase, {"soil.rheology.friction_angle=30", "time.interface_substeps=7"}).flow.numerics.air_band, 15);
  EXPECT_EQ(parse_case(two_phase, {"soil.rheology.friction_angle=30", "physics.gravity=[1.0, -9.81]"}).flow.numerics.air_band, 0);
  EXPECT_EQ(parse_case(two_phase, {"soil.rheology.friction_angle=30", "boundary.west={type = \"periodic\"}",
                                   "boundary.east={type = \"periodic\"}"})
                .flow.numerics.air_band,
            0);
  const CaseConfig projection = parse_case(two_phase, {"soil.rheology.friction_angle=30", "numerics.pressure_coupling=projection"});
  EXPECT_EQ(projection.flow.numerics.air_band, 0);
  // A Newtonian soil: the projection, the cells' evaluations.
  std::string newtonian(two_phase);
  newtonian.erase(newtonian.find("[soil.rheology]"),
                  std::string("[soil.rheology]\nmodel = \"drucker_prager_bingham\"\nfriction_angle = 95.0\n").size());
  const CaseConfig water = parse_case(newtonian, {"soil.viscosity=1e-3"});
  EXPECT_EQ(water.flow.numerics.pressure_coupling, PressureCoupling::projection);
  EXPECT_EQ(water.flow.numerics.air_band, 0);
  EXPECT_EQ(water.soil->yield_pressure, YieldPressure::cell);
  EXPECT_EQ(water.soil->face_fraction, FaceFraction::cells);
}

// soil.surface_tension: N/m, none by default; a negative one is named, and so is a misspelt key.
TEST(CaseFile, SurfaceTension) {
  const std::string phi = "soil.rheology.friction_angle=30";
  EXPECT_EQ(parse_case(two_phase, {phi}).soil->surface_tension, 0.0);
  EXPECT_EQ(parse_case(two_phase, {phi, "soil.surface_tension=0.072"}).soil->surface_tension, 0.072);
  const std::string negative = error_of(two_phase, {phi, "soil.surface_tension=-0.072"});
  EXPECT_NE(negative.find("soil.surface_tension"), std::string::npos) << negative;
  EXPECT_NE(negative.find("zero or positive"), std::string::npos) << negative;
  const std::string misspelt = error_of(two_phase, {phi, "soil.surface_tensoin=0.072"});
  EXPECT_NE(misspelt.find("surface_tension"), std::string::npos) << misspelt;
  // The contact angle: 90 deg by default, in [1, 179], and only with a surface tension to act through.
  EXPECT_EQ(parse_case(two_phase, {phi, "soil.surface_tension=0.072"}).soil->contact_angle, 90.0);
  EXPECT_EQ(parse_case(two_phase, {phi, "soil.surface_tension=0.072", "soil.contact_angle=60"}).soil->contact_angle,
            60.0);
  const std::string flat = error_of(two_phase, {phi, "soil.surface_tension=0.072", "soil.contact_angle=180"});
  EXPECT_NE(flat.find("soil.contact_angle"), std::string::npos) << flat;
  const std::string alone = error_of(two_phase, {phi, "soil.contact_angle=60"});
  EXPECT_NE(alone.find("needs soil.surface_tension"), std::string::npos) << alone;
}

// time.rest_speed: soil cases only, whose soil carries its displacement (which tells that it moved).
TEST(CaseFile, RestSpeedNeedsSoilThatCarriesItsDisplacement) {
  EXPECT_EQ(parse_case(two_phase, {"soil.rheology.friction_angle=30", "time.rest_speed=1e-3"}).time.rest_speed, 1e-3);
  EXPECT_EQ(parse_case(two_phase, {"soil.rheology.friction_angle=30"}).time.rest_speed, 0.0);
  const std::string hidden =
      error_of(two_phase, {"soil.rheology.friction_angle=30", "time.rest_speed=1e-3", "soil.displacement=false"});
  EXPECT_NE(hidden.find("time.rest_speed: needs soil.displacement = true"), std::string::npos) << hidden;
  const std::string negative = error_of(two_phase, {"soil.rheology.friction_angle=30", "time.rest_speed=-1"});
  EXPECT_NE(negative.find("time.rest_speed: -1 is invalid"), std::string::npos) << negative;
  const std::string fluid = error_of(minimal, {"time.rest_speed=1e-3"});
  EXPECT_NE(fluid.find("time.rest_speed: applies to cases with soil only"), std::string::npos) << fluid;
}

TEST(CaseFile, AirBandNeedsTheCoupledSolveAndSoil) {
  const std::vector<std::string> valid{"soil.rheology.friction_angle=30", "numerics.pressure_coupling=coupled"};
  auto with = [&](const std::string& extra) {
    auto o = valid;
    o.push_back(extra);
    return o;
  };
  EXPECT_EQ(parse_case(two_phase, with("numerics.air_band=0")).flow.numerics.air_band, 0);
  EXPECT_EQ(parse_case(two_phase, with("numerics.air_band=20")).flow.numerics.air_band, 20);
  for (const char* bad : {"numerics.air_band=-1", "numerics.air_band=2.5"}) {
    const std::string e = error_of(two_phase, with(bad));
    EXPECT_NE(e.find("numerics.air_band"), std::string::npos) << bad << ": " << e;
  }
  // Wider than a step moves the soil: each of 5 sweeps may carry it a cell further, so the band,
  // laid again once the soil is within half of it of its edge, needs 11.
  auto sweeps = with("time.interface_substeps=5");
  sweeps.push_back("numerics.air_band=10");
  const std::string narrow = error_of(two_phase, sweeps);
  EXPECT_NE(narrow.find("numerics.air_band = 10: too narrow for steps of 5 sweep(s)"), std::string::npos) << narrow;
  EXPECT_NE(narrow.find("at least 11"), std::string::npos) << narrow;
  sweeps.back() = "numerics.air_band=11";
  EXPECT_EQ(error_of(two_phase, sweeps), "");
  EXPECT_EQ(error_of(two_phase, with("numerics.air_band=3")), "");  // one sweep: one cell
  EXPECT_NE(error_of(two_phase, with("numerics.air_band=2")).find("at least 3"), std::string::npos);
  const std::string projection =
      error_of(two_phase, {"soil.rheology.friction_angle=30", "numerics.air_band=12", "numerics.pressure_coupling=projection"});
  EXPECT_NE(projection.find("numerics.air_band"), std::string::npos) << projection;
  EXPECT_NE(projection.find("coupled"), std::string::npos) << projection;
  auto closed_top = with("numerics.air_band=12");  // the air beyond the band below a zero top
  closed_top.push_back("boundary.north={type=\"wall\"}");
  EXPECT_EQ(error_of(two_phase, closed_top), "");
  const std::string no_soil = error_of(minimal, {"numerics.pressure_coupling=coupled", "numerics.air_band=4"});
  EXPECT_NE(no_soil.find("numerics.air_band"), std::string::npos) << no_soil;
}

// The coupled solve is accepted in a closed domain (it holds the pressure level in a continuity row,
// PressureLevel.ClosedDomainUnderTheCoupledSolve) and with an open side.
TEST(CaseFile, CoupledSolveInAClosedDomainOrWithAnOpenSideIsAccepted) {
  const CaseConfig closed = parse_case(minimal, {"numerics.pressure_coupling=coupled"});
  EXPECT_EQ(closed.flow.numerics.pressure_coupling, PressureCoupling::coupled);
  EXPECT_EQ(boundary(closed.flow.boundaries, Side::north).kind, BoundaryKind::wall);
  const CaseConfig open = parse_case(minimal, {"numerics.pressure_coupling=coupled", "boundary.north={type=\"atmosphere\"}"});
  EXPECT_EQ(open.flow.numerics.pressure_coupling, PressureCoupling::coupled);
  EXPECT_EQ(boundary(open.flow.boundaries, Side::north).kind, BoundaryKind::atmosphere);
}

// A Cholesky factor of a matrix that is not symmetric positive definite solves another system.
TEST(CaseFile, CholeskyOnlyForThePressure) {
  for (const char* pc : {"icc", "cholesky"}) {
    const std::string momentum = error_of(minimal, {std::string("solver.momentum.pc_type=") + pc});
    EXPECT_NE(momentum.find("solver.momentum.pc_type"), std::string::npos) << momentum;
    const std::string coupled = error_of(minimal, {std::string("solver.coupled.pc_type=") + pc});
    EXPECT_NE(coupled.find("solver.coupled.pc_type"), std::string::npos) << coupled;
    EXPECT_EQ(error_of(minimal, {std::string("solver.pressure.pc_type=") + pc}), "") << pc;
  }
}

TEST(CaseFile, LineNamesCannotBeThoseOfOtherOutputFiles) {
  const auto line = [](const std::string& name) {
    return std::string(minimal) + "[[output.line]]\nname = \"" + name + "\"\nstart = [0.0, 0.5]\nend = [1.0, 0.5]\n";
  };
  EXPECT_EQ(error_of(line("profile_2")), "");
  EXPECT_EQ(error_of(line("x_1a")), "");
  for (const char* bad : {"", "surface_00001", "a_00000", "history", "stability", "a b"}) {
    const std::string e = error_of(line(bad));
    EXPECT_NE(e.find("output.line"), std::string::npos) << "'" << bad << "': " << e;
  }
  // Its files' names must fit the file system's 255 bytes while they are written (.NAME_NNNNN.csv.tmpPID).
  EXPECT_EQ(error_of(line(std::string(200, 'a'))), "");
  EXPECT_NE(error_of(line(std::string(201, 'a'))).find("output.line[0].name: 201 characters, more than 200"),
            std::string::npos);
}

// A line that ends where it starts samples one point a hundred times.
TEST(CaseFile, LineMustHaveALength) {
  const std::string text =
      std::string(minimal) + "[[output.line]]\nname = \"dot\"\nstart = [0.5, 0.5]\nend = [0.5, 0.5]\n";
  EXPECT_NE(error_of(text).find("output.line[0].end: the line ends where it starts"), std::string::npos) << error_of(text);
}

TEST(CaseFile, PolygonsMayCloseTheirOutlineButNotCrossIt) {
  const auto with_polygon = [](const std::string& points) {
    return std::vector<std::string>{"soil.rheology.friction_angle=30",
                                    "initial.soil=[{shape = \"polygon\", points = " + points + "}]"};
  };
  const CaseConfig closed = parse_case(two_phase, with_polygon("[[0,0],[0.2,0],[0.2,0.1],[0,0.1],[0,0]]"));
  EXPECT_EQ(std::get<interface::Polygon>(closed.soil->initial_soil[0]).vertices.size(), 4u);
  // A long, thin triangle (1e12 m by 0.1 m) encloses an area, though a small one against its length squared.
  const CaseConfig thin = parse_case(two_phase, with_polygon("[[0,0],[1e12,0],[0.2,0.1]]"));
  EXPECT_EQ(std::get<interface::Polygon>(thin.soil->initial_soil[0]).vertices.size(), 3u);
  // Each outline refused with its own message.
  const std::pair<const char*, const char*> refused[] = {
      {"[[0,0],[0.2,0.1],[0.2,0],[0,0.1]]", "crosses itself"},
      {"[[0,0],[0.2,0],[0.2,0],[0,0]]", "3 distinct points"},
      // points on one line enclose nothing: said so, not blamed on the domain
      {"[[0,0],[0.1,0],[0.2,0]]", "initial.soil[0].points: the polygon encloses no area (its points lie on one line)"},
      // a triangle of a nanometre inside the domain: not outside it, but too small to count
      {"[[0.1,0.1],[0.100000001,0.1],[0.1,0.100000001]]",
       "covers next to no area of the domain [0, 1] x [0, 1] (less than 1e-12 of it: a shape far smaller than a cell)"},
      {"[[2,2],[3,2],[2,3]]", "covers no area of the domain [0, 1] x [0, 1]"},
      // an unknown key lists the polygon's keys, points_file (read before the shape) among them
      {"[[0,0],[0.2,0],[0,0.1]], colour = 1",
       "initial.soil[0].colour: unknown key (known keys here: material, points, points_file, shape)"}};
  for (const auto& [points, message] : refused) {
    const std::string e = error_of(two_phase, with_polygon(points));
    EXPECT_NE(e.find(message), std::string::npos) << points << ": " << e;
  }
}

// A required key or table that is missing because it is misspelt is reported as the misspelling: the
// key that stands in its place, a letter or two off or with two letters swapped, is named too.
TEST(CaseFile, MissingKeyNamesItsMisspelling) {
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string side = error_of(replaced(minimal, "west =", "wset ="));
  EXPECT_NE(side.find("boundary.west: missing"), std::string::npos) << side;
  EXPECT_NE(side.find("boundary.wset is not a key: west misspelt?"), std::string::npos) << side;
  const std::string table = error_of(replaced(minimal, "[mesh]", "[mseh]"));
  EXPECT_NE(table.find("mesh: missing table [mesh]; mseh is not a key: mesh misspelt?"), std::string::npos) << table;
  const std::string number = error_of(replaced(minimal, "end = 1.0", "edn = 1.0"));
  EXPECT_NE(number.find("time.end: missing"), std::string::npos) << number;
  EXPECT_NE(number.find("time.edn is not a key"), std::string::npos) << number;
  const std::string shapes =
      error_of(replaced(two_phase, "[[initial.soil]]", "[[initial.soils]]"), {"soil.rheology.friction_angle=30"});
  EXPECT_NE(shapes.find("initial.soils is not a key: soil misspelt?"), std::string::npos) << shapes;
  // A side missing is not taken for another side, valid but read later (east is one edit from west).
  std::string no_west = minimal;
  no_west.erase(no_west.find("west ="), std::string("west = { type = \"wall\" }\n").size());
  const std::string absent = error_of(no_west);
  EXPECT_NE(absent.find("boundary.west: missing"), std::string::npos) << absent;
  EXPECT_EQ(absent.find("misspelt"), std::string::npos) << absent;
  // Far from every missing key: no guess.
  const std::string unrelated = error_of(replaced(minimal, "end = 1.0", "duration = 1.0"));
  EXPECT_EQ(unrelated.find("misspelt"), std::string::npos) << unrelated;
}

// --set takes one key and one value: an element of an array of tables is not addressable, and a value
// with more keys on further lines (which would be dropped) is refused.
TEST(CaseFile, SetRefusesArrayElementsAndValuesOverSeveralLines) {
  const std::string element = error_of(two_phase, {"soil.rheology.friction_angle=30", "initial.soil[0].upper=[0.3, 0.1]"});
  EXPECT_NE(element.find("an element of an array cannot be set alone; set the whole array, --set 'initial.soil=[...]'"),
            std::string::npos)
      << element;
  // So is a key under one (initial.soil is an array of tables, not a table).
  const std::string under = error_of(two_phase, {"soil.rheology.friction_angle=30", "initial.soil.upper=[0.3, 0.1]"});
  EXPECT_NE(under.find("an element of an array cannot be set alone; set the whole array, --set 'initial.soil=[...]'"),
            std::string::npos)
      << under;
  // An array of numbers likewise, named as such.
  const std::string cells = error_of(minimal, {"mesh.cells[0]=5"});
  EXPECT_NE(cells.find("set the whole array, --set 'mesh.cells=[...]'"), std::string::npos) << cells;
  // A quoted key would be taken with its quotes; text that is not UTF-8 could not be recorded as TOML.
  const std::string quoted = error_of(minimal, {"\"mesh\".cells=[3, 3]"});
  EXPECT_NE(quoted.find("write the key without quotes"), std::string::npos) << quoted;
  const std::string latin1 = error_of(minimal, {"title=caf\xe9"});
  EXPECT_NE(latin1.find("--set 'title=caf\\xE9': the text is not valid UTF-8"), std::string::npos) << latin1;
  EXPECT_EQ(parse_case(minimal, {"title=caf\xc3\xa9"}).title, "caf\xc3\xa9");
  const std::string lines = error_of(minimal, {"time.end=0.02\nmesh.cells=[1, 1]"});
  EXPECT_NE(lines.find("more than one key"), std::string::npos) << lines;
  // A value that is one TOML value over several lines is one value.
  EXPECT_EQ(parse_case(minimal, {"mesh.cells=[16,\n 8]"}).mesh.cells[1], 8);
}

// A bare word is a string; a value that starts as a number, a string, an array or a table and does not
// parse is named as such (it became a string, and the message named the wrong problem, or none).
TEST(CaseFile, SetNamesAValueThatIsNotToml) {
  for (const char* bad : {"mesh.cells=[16,8", "time.end=1e400", "title=\"abc", "time={end=1.0, end=2.0}"}) {
    const std::string message = error_of(minimal, {bad});
    EXPECT_NE(message.find(fmt::format("--set '{}': the value is not valid TOML: ", bad)), std::string::npos) << message;
  }
  EXPECT_EQ(parse_case(minimal, {"title=a title of words"}).title, "a title of words");
}

// A key the case's other choices make of no effect is accepted (a case may keep it for switching
// numerics with --set) and listed, for `check` and `run` to warn of.
TEST(CaseFile, KeysWithoutEffectAreListed) {
  EXPECT_TRUE(parse_case(minimal).keys_without_effect.empty());
  const CaseConfig c = parse_case(minimal, {"numerics.blending=0.5", "numerics.pressure_correctors=3",
                                            "time.adaptive=false", "time.courant=0.3"});
  ASSERT_EQ(c.keys_without_effect.size(), 3u);
  EXPECT_NE(c.keys_without_effect[0].find("time.courant: time.adaptive = false"), std::string::npos) << c.keys_without_effect[0];
  EXPECT_NE(c.keys_without_effect[1].find("numerics.blending: used only with numerics.convection = \"blended\""),
            std::string::npos) << c.keys_without_effect[1];
  EXPECT_NE(c.keys_without_effect[2].find("numerics.pressure_correctors"), std::string::npos) << c.keys_without_effect[2];
  EXPECT_TRUE(parse_case(minimal, {"numerics.blending=0.5", "numerics.convection=blended"}).keys_without_effect.empty());
  const CaseConfig soil = parse_case(two_phase, {"soil.rheology.friction_angle=30", "soil.displacement=false",
                                                 "soil.failure_strain=0.2"});
  ASSERT_EQ(soil.keys_without_effect.size(), 1u);
  EXPECT_NE(soil.keys_without_effect[0].find("soil.failure_strain"), std::string::npos);
}

// The later outer iterations by the first one's factorisation: warned of where nothing uses them,
// refused where the factorisation would not be the first iteration's own exact LU.
TEST(CaseFile, FirstFactorisationIsWarnedOfWhereUnusedAndRefusedWhereInexact) {
  const std::string coupled = "numerics.pressure_coupling=coupled";
  const std::string first = "numerics.later_iterations=first_factorisation";
  EXPECT_TRUE(parse_case(minimal, {coupled, first, "numerics.krylov_iterations=3"}).keys_without_effect.empty());
  EXPECT_TRUE(parse_case(minimal, {coupled, first}).flow.numerics.reuse_first_factorisation);
  const CaseConfig projection = parse_case(minimal, {first});
  ASSERT_EQ(projection.keys_without_effect.size(), 1u);
  EXPECT_NE(projection.keys_without_effect[0].find("numerics.later_iterations: used only with numerics.pressure_coupling"),
            std::string::npos) << projection.keys_without_effect[0];
  EXPECT_FALSE(projection.flow.numerics.reuse_first_factorisation);
  const CaseConfig one = parse_case(minimal, {coupled, first, "numerics.outer_iterations=1", "numerics.krylov_iterations=3"});
  ASSERT_EQ(one.keys_without_effect.size(), 2u);
  EXPECT_NE(one.keys_without_effect[0].find("numerics.later_iterations: \"first_factorisation\" has no effect with "
                                            "numerics.outer_iterations = 1"), std::string::npos) << one.keys_without_effect[0];
  EXPECT_NE(one.keys_without_effect[1].find("numerics.krylov_iterations: used only with"), std::string::npos)
      << one.keys_without_effect[1];
  EXPECT_FALSE(one.flow.numerics.reuse_first_factorisation);
  // Of no effect there, it binds the coupled solver to nothing.
  EXPECT_EQ(error_of(minimal, {coupled, first, "numerics.outer_iterations=1", "solver.coupled.pc_type=\"hypre\""}), "");
  const CaseConfig own = parse_case(minimal, {coupled, "numerics.krylov_iterations=3"});
  ASSERT_EQ(own.keys_without_effect.size(), 1u);
  EXPECT_NE(own.keys_without_effect[0].find("numerics.krylov_iterations"), std::string::npos);
  const std::string amg = error_of(minimal, {coupled, first, "solver.coupled.pc_type=\"hypre\""});
  EXPECT_NE(amg.find("needs solver.coupled.pc_type = \"lu\" or \"redundant\" (it is \"hypre\")"), std::string::npos) << amg;
  const std::string reused = error_of(minimal, {coupled, first, "solver.coupled.reuse_preconditioner=2"});
  EXPECT_NE(reused.find("needs solver.coupled.reuse_preconditioner = 1"), std::string::npos) << reused;
  EXPECT_NE(error_of(minimal, {coupled, first, "numerics.krylov_iterations=0"}).find("numerics.krylov_iterations"),
            std::string::npos);
}

// A key that another choice of the case leaves unused says which choice, not "unknown key"; a
// misspelt [soil.rheology] is named as such, not as a missing soil.viscosity.
TEST(CaseFile, KeysOfAnotherChoiceAndAMisspeltRheologyAreNamed) {
  std::string misspelt = two_phase;
  misspelt.replace(misspelt.find("[soil.rheology]"), 15, "[soil.rheolgy]");
  const std::string table = error_of(misspelt);
  EXPECT_NE(table.find("soil: neither a [soil.rheology] table"), std::string::npos) << table;
  EXPECT_NE(table.find("soil.rheolgy is not a key: rheology misspelt?"), std::string::npos) << table;
  const std::string both = error_of(two_phase, {"soil.rheology.friction_angle=30", "soil.viscosity=1.0"});
  EXPECT_NE(both.find("soil.viscosity: used only without [soil.rheology]"), std::string::npos) << both;
  const CaseConfig linear = parse_case(two_phase, {"soil.rheology.friction_angle=30", "mixture.arctan_M=-0.45"});
  ASSERT_EQ(linear.keys_without_effect.size(), 1u);
  EXPECT_NE(linear.keys_without_effect[0].find("mixture.arctan_M: used only with mixture.density or mixture.viscosity = "
                                               "\"arctan\""), std::string::npos) << linear.keys_without_effect[0];
  EXPECT_TRUE(parse_case(two_phase, {"soil.rheology.friction_angle=30", "mixture.arctan_M=-0.45", "mixture.density=arctan"})
                  .keys_without_effect.empty());
  // Unused, the constants are still held to their ranges, as an unused numerics.blending is.
  const std::string shift = error_of(two_phase, {"soil.rheology.friction_angle=30", "mixture.arctan_M=5"});
  EXPECT_NE(shift.find("mixture.arctan_M"), std::string::npos) << shift;
  const std::string steepness = error_of(two_phase, {"soil.rheology.friction_angle=30", "mixture.arctan_N=-3"});
  EXPECT_NE(steepness.find("mixture.arctan_N"), std::string::npos) << steepness;
}

TEST(CaseFile, ShippedCasesAreValid) {
  for (const char* name : {"lid_driven_cavity_re100", "lid_driven_cavity_re1000", "bui2008_experiment"})
    EXPECT_NO_THROW(load_case(std::string(GRANFLOW_SOURCE_DIR) + "/cases/" + name + ".toml")) << name;
}

}  // namespace
}  // namespace granflow

namespace granflow {
namespace {

// The coupled solver's count is a Krylov method's (its default preonly applies the factorisation once
// whatever the count): a Krylov method given without a count takes 1000, so that its solves are not
// each stopped after one iteration.
TEST(CaseFile, CoupledKrylovMethodWithoutACountTakesAKrylovCount) {
  const std::string phi = "soil.rheology.friction_angle=30";
  EXPECT_EQ(parse_case(two_phase, {phi}).flow.coupled_solver.max_iterations, 1000);
  EXPECT_EQ(parse_case(two_phase, {phi, "solver.coupled.ksp_type=\"gmres\""}).flow.coupled_solver.max_iterations, 1000);
  EXPECT_EQ(parse_case(two_phase, {phi, "solver.coupled.ksp_type=\"gmres\"", "solver.coupled.max_iterations=2"})
                .flow.coupled_solver.max_iterations,
            2);
  EXPECT_EQ(parse_case(two_phase, {phi, "solver.coupled.ksp_type=\"preonly\""}).flow.coupled_solver.max_iterations, 1000);
}

// An error in a key that --set gave (or in an entry under it) names the command line, not the case file,
// which may not hold the key at all; one in the file's own keys names the file.
TEST(CaseFile, ErrorsInSetKeysNameTheCommandLine) {
  const std::string bui = std::string(GRANFLOW_SOURCE_DIR) + "/cases/bui2008_experiment.toml";
  auto error_loading = [](const std::filesystem::path& file, const std::vector<std::string>& overrides) {
    try {
      load_case(file, overrides);
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto message = [&](const std::vector<std::string>& overrides) { return error_loading(bui, overrides); };
  EXPECT_EQ(message({"mesh.cels=3"}).rfind("--set mesh.cels: unknown key", 0), 0u) << message({"mesh.cels=3"});
  const std::string ring =
      message({"initial.soil=[{shape = \"ring\", centre = [0.3, 0.05], inner_radius = 0.05, outer_radius = 0.04}]"});
  EXPECT_EQ(ring.rfind("--set initial.soil[0].outer_radius: the ring is empty", 0), 0u) << ring;
  const std::string spaced = message({" time.courant = -1"});
  EXPECT_EQ(spaced.rfind("--set time.courant: ", 0), 0u) << spaced;
  // A table's rheology check of a key --set gave; a message that quotes its value after the key; blanks
  // around the dots; an assignment that cannot be applied.
  const std::string phi = message({"soil.rheology.friction_angle=95"});
  EXPECT_EQ(phi.rfind("--set soil.rheology: rheology parameter friction_angle", 0), 0u) << phi;
  const std::string band = message({"numerics.air_band=2"});
  EXPECT_EQ(band.rfind("--set numerics.air_band = 2: too narrow", 0), 0u) << band;
  const std::string dots = message({"time . courant=-1"});
  EXPECT_EQ(dots.rfind("--set time.courant: ", 0), 0u) << dots;
  EXPECT_EQ(message({"foo"}), "--set 'foo': expected KEY=VALUE");
  // The file's own key in error, with --set giving others: the file's; so too where an assigned key
  // begins the erring key's name (output.interval is not output.intervalx) or the rheology check names
  // another parameter than the one assigned.
  const auto dir = std::filesystem::temp_directory_path() / "granflow_set_or_file";
  std::filesystem::create_directories(dir);
  const auto bad = dir / "bad.toml";
  {
    std::ofstream out(bad);
    out << read_text_file(bui, 1 << 20).text << "\nintervalx = 1\n";  // in its last table, [output]
  }
  auto file_error = [&](const std::vector<std::string>& overrides) { return error_loading(bad, overrides); };
  const std::string prefix = file_error({"mesh.cells=[30,10]", "output.interval=0.5"});
  EXPECT_EQ(prefix.rfind(bad.string() + ": output.intervalx: unknown key", 0), 0u) << prefix;
  {
    std::ofstream out(bad);
    std::string text = read_text_file(bui, 1 << 20).text;
    text.replace(text.find("friction_angle = 19.8"), std::string("friction_angle = 19.8").size(), "friction_angle = 95");
    out << text;
  }
  const std::string other = file_error({"soil.rheology.cohesion=10"});
  EXPECT_EQ(other.rfind(bad.string() + ": soil.rheology: rheology parameter friction_angle", 0), 0u) << other;
  std::filesystem::remove_all(dir);
}

// An axisymmetric mesh's gravity acts along its axis: a radial component is refused by the key.
TEST(CaseFile, AxisymmetricGravityAlongTheAxisOnly) {
  const std::vector<std::string> axisymmetric{"soil.rheology.friction_angle=30", "mesh.geometry=\"axisymmetric\"",
                                              "boundary.west={type = \"axis\"}"};
  EXPECT_TRUE(parse_case(two_phase, axisymmetric).mesh.axisymmetric);
  auto radial = axisymmetric;
  radial.push_back("physics.gravity=[-9.81, 0.0]");
  const std::string e = error_of(two_phase, radial);
  EXPECT_NE(e.find("physics.gravity: -9.81 along r in an axisymmetric mesh"), std::string::npos) << e;
}

// shape = "ring": its centre and two radii, the hole's smaller; a ring without area, or one given a
// circle's radius, is refused by the key.
TEST(CaseFile, RingsTakeACentreAndTwoRadii) {
  const std::string phi = "soil.rheology.friction_angle=30";
  const std::string ring = "initial.soil=[{shape = \"ring\", centre = [0.5, 0.1], inner_radius = 0.05, outer_radius = 0.1}]";
  const CaseConfig c = parse_case(two_phase, {phi, ring});
  ASSERT_EQ(c.soil->initial_soil.size(), 1u);
  const auto* parsed = std::get_if<interface::Ring>(&c.soil->initial_soil[0]);
  ASSERT_NE(parsed, nullptr);
  EXPECT_EQ(parsed->inner_radius, 0.05);
  EXPECT_EQ(parsed->outer_radius, 0.1);
  const std::string empty = error_of(
      two_phase, {phi, "initial.soil=[{shape = \"ring\", centre = [0.5, 0.1], inner_radius = 0.1, outer_radius = 0.1}]"});
  EXPECT_NE(empty.find("initial.soil[0].outer_radius"), std::string::npos) << empty;
  EXPECT_NE(empty.find("ring is empty"), std::string::npos) << empty;
  const std::string negative = error_of(
      two_phase, {phi, "initial.soil=[{shape = \"ring\", centre = [0.5, 0.1], inner_radius = -0.1, outer_radius = 0.1}]"});
  EXPECT_NE(negative.find("inner_radius"), std::string::npos) << negative;
  const std::string around = error_of(
      two_phase, {phi, "initial.soil=[{shape = \"ring\", centre = [0.5, 0.1], inner_radius = 5, outer_radius = 6}]"});
  EXPECT_NE(around.find("the ring's hole (radius 5 about [0.5, 0.1]) holds the whole domain"), std::string::npos) << around;
  const std::string circle_key = error_of(
      two_phase, {phi, "initial.soil=[{shape = \"ring\", centre = [0.5, 0.1], radius = 0.1, outer_radius = 0.2}]"});
  EXPECT_NE(circle_key.find("inner_radius"), std::string::npos) << circle_key;
}

// [[obstacle]]: the shapes of initial.soil, refused where the solver does not know blocked cells.
TEST(CaseFile, ObstaclesTakeShapesAndNeedTheCoupledSolveOffTheAxis) {
  const std::vector<std::string> coupled{"soil.rheology.friction_angle=30", "numerics.pressure_coupling=coupled"};
  auto with = [&](std::vector<std::string> extra) {
    auto o = coupled;
    o.insert(o.end(), extra.begin(), extra.end());
    return o;
  };
  const std::string step = "obstacle=[{shape = \"box\", lower = [0.6, 0.0], upper = [1.0, 0.2]}, "
                           "{shape = \"circle\", centre = [0.8, 0.6], radius = 0.1}]";
  const CaseConfig c = parse_case(two_phase, with({step}));
  ASSERT_EQ(c.obstacles.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<interface::Circle>(c.obstacles[1]));
  EXPECT_TRUE(parse_case(two_phase, coupled).obstacles.empty());
  const std::string projection =
      error_of(two_phase, {"soil.rheology.friction_angle=30", "numerics.pressure_coupling=projection", step});
  EXPECT_NE(projection.find("obstacle"), std::string::npos) << projection;
  EXPECT_NE(projection.find("coupled"), std::string::npos) << projection;
  const std::string outside =
      error_of(two_phase, with({"obstacle=[{shape = \"box\", lower = [2.0, 0.0], upper = [3.0, 1.0]}]"}));
  EXPECT_NE(outside.find("obstacle[0]"), std::string::npos) << outside;
  EXPECT_NE(outside.find("covers no area of the domain"), std::string::npos) << outside;
  const std::string misspelt = error_of(two_phase, with({"obstacle=[{shape = \"box\", lower = [0.6, 0.0], uper = [1.0, 0.2]}]"}));
  EXPECT_NE(misspelt.find("obstacle"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("obstacle[0].upper"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("obstacle[0].uper is not a key"), std::string::npos) << misspelt;
  const std::string axisymmetric = error_of(
      two_phase, with({step, "mesh.geometry=axisymmetric", "boundary.west={type = \"axis\"}"}));
  EXPECT_NE(axisymmetric.find("obstacle"), std::string::npos) << axisymmetric;
  EXPECT_NE(axisymmetric.find("not on an axisymmetric mesh"), std::string::npos) << axisymmetric;
}


TEST(CaseFile, MagnitudesTheSolverCannotComputeWithAreNamed) {
  const std::vector<std::string> valid = {"soil.rheology.friction_angle=30"};
  auto with = [&](std::string o) {
    auto all = valid;
    all.push_back(std::move(o));
    return all;
  };
  const std::string gravity = error_of(two_phase, with("physics.gravity=[0, -1e300]"));
  EXPECT_NE(gravity.find("physics.gravity: -1e+300 is beyond the magnitudes"), std::string::npos) << gravity;
  const std::string domain = error_of(minimal, {"mesh.upper=[1e-300, 1e-300]"});
  EXPECT_NE(domain.find("mesh.upper: 1e-300 is beyond"), std::string::npos) << domain;
  const std::string density = error_of(two_phase, with("soil.density=2e30"));
  EXPECT_NE(density.find("soil.density: 2e+30 is beyond"), std::string::npos) << density;
  const std::string point = error_of(two_phase, with("initial.soil=[{shape = \"polygon\", points = [[0, 0], [1e31, 0], [0, 1]]}]"));
  EXPECT_NE(point.find("initial.soil[0].points: 1e+31 is beyond"), std::string::npos) << point;
  // The ends of the range, zero, and tolerances below it are accepted.
  EXPECT_EQ(error_of(minimal, {"fluid.density=1e30", "fluid.viscosity=1e-30", "mesh.lower=[0, 0]"}), "");
  EXPECT_EQ(error_of(minimal, {"solver.momentum.atol=1e-50"}), "");
}

// A dotted key of 100 000 parts nests as many tables; the parser recurses through them on a stack
// sized for it.
TEST(CaseFile, DeeplyNestedKeyIsReadNotAStackOverflow) {
  std::string key;
  for (int i = 0; i < 100000; ++i) key += "a.";
  const std::string e = error_of(std::string(minimal) + "[extra]\n" + key + "b = 1\n");
  EXPECT_NE(e.find("extra: unknown key"), std::string::npos) << e.substr(0, 200);
}

// A mesh of layers: three cell counts, corners and gradings of three numbers, a front and a back side,
// gravity and wall velocities of three components, and solids among the initial shapes (planar shapes
// extruded across the depth). What it does not have yet is refused naming the key.
const char* layered = R"(
[mesh]
cells = [8, 6, 4]
lower = [0.0, 0.0, -0.2]
upper = [0.8, 0.6, 0.2]
grading = [1.0, 1.0, 0.5]
[time]
end = 0.1
[physics]
gravity = [0.0, -9.81, 0.0]
[air]
density = 1.0
viscosity = 1e-5
[soil]
density = 1500.0
[soil.rheology]
friction_angle = 30.0
[[initial.soil]]
shape = "cylinder"
centre = [0.2, 0.0]
radius = 0.1
bottom = 0.0
top = 0.2
[[initial.soil]]
shape = "box"
lower = [0.5, 0.0, -0.2]
upper = [0.8, 0.1, 0.0]
[[initial.soil]]
shape = "sphere"
centre = [0.6, 0.4, 0.1]
radius = 0.05
[[initial.soil]]
shape = "circle"
centre = [0.0, 0.0]
radius = 0.1
[boundary]
west = { type = "wall" }
east = { type = "slip" }
south = { type = "wall", velocity = [0.0, 0.0, 0.1] }
north = { type = "atmosphere" }
front = { type = "symmetry" }
back = { type = "wall" }
)";

TEST(CaseFile, AMeshOfLayersReadsItsThirdAxis) {
  const CaseConfig c = parse_case(layered);
  EXPECT_EQ(c.mesh.cells[2], 4);
  EXPECT_EQ(c.mesh.lower[2], -0.2);
  EXPECT_EQ(c.mesh.upper[2], 0.2);
  EXPECT_EQ(c.mesh.grading[2], 0.5);
  EXPECT_EQ(c.flow.boundaries[int(Side::front)].kind, BoundaryKind::slip);
  EXPECT_EQ(c.flow.boundaries[int(Side::back)].kind, BoundaryKind::wall);
  EXPECT_EQ(c.flow.boundaries[int(Side::south)].velocity[2], 0.1);
  ASSERT_TRUE(c.soil);
  ASSERT_EQ(c.soil->initial_soil_3d.size(), 3u);  // the cylinder, the box of three-number corners, the sphere
  EXPECT_TRUE(std::holds_alternative<interface::VerticalCylinder>(c.soil->initial_soil_3d[0]));
  EXPECT_TRUE(std::holds_alternative<interface::Box3>(c.soil->initial_soil_3d[1]));
  EXPECT_TRUE(std::holds_alternative<interface::Sphere>(c.soil->initial_soil_3d[2]));
  ASSERT_EQ(c.soil->initial_soil.size(), 1u);  // the circle, extruded
  EXPECT_EQ(c.soil->initial_solids(-0.2, 0.2).size(), 4u);
  // A granular soil there takes the projection and no air band, and writes checkpoints; the coupled
  // solve, when asked for, covers the soil and an air band, and moves momentum with the VoF's mass, as
  // on a planar mesh.
  EXPECT_EQ(c.flow.numerics.pressure_coupling, PressureCoupling::projection);
  EXPECT_EQ(c.flow.numerics.air_band, 0);
  const CaseConfig coupled = parse_case(layered, {"numerics.pressure_coupling=\"coupled\""});
  EXPECT_EQ(coupled.flow.numerics.pressure_coupling, PressureCoupling::coupled);
  EXPECT_EQ(coupled.flow.numerics.air_band, std::max(12, 2 * coupled.time.interface_substeps + 1));
  EXPECT_TRUE(coupled.flow.numerics.conservative_momentum);
  EXPECT_TRUE(c.output.checkpoints);
  EXPECT_EQ(c.soil->face_fraction, FaceFraction::face);
  EXPECT_EQ(parse_case(layered, {"physics.gravity=[0.0, -9.81, 1.5]"}).flow.gravity[2], 1.5);
  EXPECT_EQ(cell_counts(c.mesh), "8 x 6 x 4");
  EXPECT_EQ(std::string(volume_unit(c.mesh)), "m^3");
}

// Obstacles on a mesh of layers: solids of their own, and planar shapes extruded across the whole
// depth (a terrain profile's ridge), in the order given.
TEST(CaseFile, AMeshOfLayersReadsObstacleSolids) {
  const CaseConfig c = parse_case(
      layered, {"numerics.pressure_coupling=\"coupled\"",
                "obstacle=[{shape=\"sphere\", centre=[0.4, 0.0, 0.0], radius=0.1}, "
                "{shape=\"polygon\", points=[[0.6, 0.0], [0.8, 0.0], [0.8, 0.2]]}, "
                "{shape=\"box\", lower=[0.0, 0.0, -0.2], upper=[0.1, 0.05, 0.2], friction_angle=12.0, adhesion=3.0}]",
                "boundary.back={type=\"wall\", friction_angle=20.0}"});
  EXPECT_TRUE(c.obstacles.empty());
  ASSERT_EQ(c.obstacle_solids.size(), 3u);
  // Walls and obstacles of their own friction, as on a planar mesh.
  ASSERT_EQ(c.obstacle_friction.size(), 3u);
  EXPECT_FALSE(c.obstacle_friction[0] || c.obstacle_friction[1]);
  ASSERT_TRUE(c.obstacle_friction[2]);
  EXPECT_DOUBLE_EQ(c.obstacle_friction[2]->friction_coefficient, std::tan(12.0 * std::numbers::pi / 180.0));
  EXPECT_EQ(c.obstacle_friction[2]->adhesion, 3.0);
  ASSERT_TRUE(boundary(c.flow.boundaries, Side::back).friction);

  EXPECT_EQ(boundary(c.flow.boundaries, Side::back).friction->friction_angle_degrees, 20.0);
  EXPECT_TRUE(c.has_obstacles());
  EXPECT_TRUE(std::holds_alternative<interface::Sphere>(c.obstacle_solids[0]));
  ASSERT_TRUE(std::holds_alternative<interface::Extrusion>(c.obstacle_solids[1]));
  const auto& ridge = std::get<interface::Extrusion>(c.obstacle_solids[1]);
  EXPECT_EQ(ridge.z_lower, -0.2);
  EXPECT_EQ(ridge.z_upper, 0.2);
  EXPECT_TRUE(interface::contains(c.obstacle_solids[1], 0.79, 0.1, 0.15));
  EXPECT_FALSE(interface::contains(c.obstacle_solids[1], 0.61, 0.1, 0.15));
  EXPECT_TRUE(std::holds_alternative<interface::Box3>(c.obstacle_solids[2]));
  EXPECT_FALSE(parse_case(layered).has_obstacles());
}

// A height map (terrain from an elevation model) is a solid of a mesh of layers: given inline, or read
// from an ESRI ASCII grid beside the case into the case as run. What is not a grid, an empty solid, the
// file with another shape or beside the inline nodes, and a height map on a planar mesh are refused.
TEST(CaseFile, AHeightMapIsASolidOfAMeshOfLayers) {
  const std::string coupled = "numerics.pressure_coupling=\"coupled\"";
  const std::string inline_map =
      "obstacle=[{shape=\"height_map\", origin=[0.0, -0.2], spacing=[0.4, 0.2], "
      "heights=[[0.1, 0.2, 0.3], [0.1, 0.2, 0.35], [0.1, 0.25, 0.3]]}]";
  const CaseConfig c = parse_case(layered, {coupled, inline_map});
  ASSERT_EQ(c.obstacle_solids.size(), 1u);
  const auto& map = std::get<interface::HeightMap>(c.obstacle_solids[0]);
  EXPECT_EQ(map.nx, 3);
  EXPECT_EQ(map.nz, 3);
  EXPECT_EQ(map.spacing, (std::array<double, 2>{0.4, 0.2}));
  EXPECT_EQ(map.heights[5], 0.35);  // row 1 along z, node 2 along x
  EXPECT_TRUE(std::isinf(map.bottom));
  // As terrain it lowers its ridges one cell wide to the mesh unless asked to refuse them.
  EXPECT_EQ(c.obstacle_lowers_thin_ridges, std::vector<bool>{true});
  std::string refusing = inline_map;
  refusing.insert(refusing.find("origin"), "thin_ridges=\"refuse\", ");
  EXPECT_EQ(parse_case(layered, {coupled, refusing}).obstacle_lowers_thin_ridges, std::vector<bool>{false});
  EXPECT_EQ(parse_case(layered, {coupled, "obstacle=[{shape=\"sphere\", centre=[0.4, 0.0, 0.0], radius=0.1}]"})
                .obstacle_lowers_thin_ridges, std::vector<bool>{false});

  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("granflow_height_map_case_" + std::to_string(::getpid()));
  fs::create_directories(dir / "terrain");
  std::ofstream(dir / "terrain" / "dem.asc") << "ncols 3\nnrows 3\nxllcenter 0\nyllcenter -0.2\ncellsize 0.2\n"
                                                "0.3 0.3 0.3\n0.2 0.2 0.2\n0.1 0.1 0.1\n";
  const fs::path source = dir / "case.toml";
  const CaseConfig from_file = parse_case(
      layered, {"initial.soil=[{shape=\"height_map\", heights_file=\"terrain/dem.asc\", bottom=0.0}]"}, source);
  ASSERT_EQ(from_file.soil->initial_soil_3d.size(), 1u);
  const auto& soil = std::get<interface::HeightMap>(from_file.soil->initial_soil_3d[0]);
  EXPECT_EQ(soil.heights, (std::vector<double>{0.1, 0.1, 0.1, 0.2, 0.2, 0.2, 0.3, 0.3, 0.3}));
  EXPECT_EQ(soil.bottom, 0.0);
  EXPECT_NE(from_file.as_run.find("heights = [ [ 0.1, 0.1, 0.1 ]"), std::string::npos) << from_file.as_run;
  EXPECT_EQ(from_file.as_run.find("heights_file"), std::string::npos) << from_file.as_run;
  // A model reaching far beyond the domain is read as the nodes over it: a 30 x 30 grid of 0.1 m from
  // (-1, -1) over the domain's [0, 0.8] x [-0.2, 0.2] keeps 10 x 6 nodes, x from -0.05 to 0.85 m.
  {
    std::ofstream big(dir / "terrain" / "big.asc");
    big << "ncols 30\nnrows 30\nxllcorner -1.0\nyllcorner -1.0\ncellsize 0.1\n";
    for (int r = 0; r < 30; ++r) {
      for (int i = 0; i < 30; ++i) big << 0.01 * (i + r) << ' ';
      big << '\n';
    }
  }
  const CaseConfig cut = parse_case(
      layered, {"initial.soil=[{shape=\"height_map\", heights_file=\"terrain/big.asc\", bottom=-1.0}]"}, source);
  const auto& kept = std::get<interface::HeightMap>(cut.soil->initial_soil_3d[0]);
  EXPECT_EQ(kept.nx, 10);
  EXPECT_EQ(kept.nz, 6);
  EXPECT_NEAR(kept.origin[0], -0.05, 1e-12);
  EXPECT_NEAR(kept.origin[1], -0.25, 1e-12);
  // `offset` moves a map in survey coordinates to the mesh's: x and z to the origin, y to the heights.
  const CaseConfig moved = parse_case(
      layered, {"initial.soil=[{shape=\"height_map\", heights_file=\"terrain/dem.asc\", offset=[0.1, -0.05, 0.2]}]"},
      source);
  const auto& shifted = std::get<interface::HeightMap>(moved.soil->initial_soil_3d[0]);
  EXPECT_EQ(shifted.origin, (std::array<double, 2>{0.1, 0.0}));
  ASSERT_EQ(shifted.nz, 2);  // moved along z by 0.2 m, the domain's z up to 0.2 m needs the rows at 0 and 0.2 m
  EXPECT_NEAR(shifted.heights[5], 0.15, 1e-15);
  // The case as run reads back to the same map.
  EXPECT_EQ(std::get<interface::HeightMap>(parse_case(from_file.as_run).soil->initial_soil_3d[0]).heights, soil.heights);

  auto error = [&](const std::string& obstacle) { return error_of(layered, {coupled, obstacle}, source); };
  const std::string ragged = error("obstacle=[{shape=\"height_map\", origin=[0.0, 0.0], spacing=[0.1, 0.1], "
                                   "heights=[[0.1, 0.2, 0.3], [0.1, 0.2]]}]");
  EXPECT_NE(ragged.find("obstacle[0].heights: row 2 holds 2 numbers and row 1 3"), std::string::npos) << ragged;
  const std::string single = error("obstacle=[{shape=\"height_map\", origin=[0.0, 0.0], spacing=[0.1, 0.1], "
                                   "heights=[[0.1, 0.2, 0.3]]}]");
  EXPECT_NE(single.find("obstacle[0].heights: expected an array of at least 2 rows"), std::string::npos) << single;
  const std::string spacing = error("obstacle=[{shape=\"height_map\", origin=[0.0, 0.0], spacing=[0.1, -0.1], "
                                    "heights=[[0.1, 0.2], [0.1, 0.2]]}]");
  EXPECT_NE(spacing.find("obstacle[0].spacing: expected two positive numbers"), std::string::npos) << spacing;
  const std::string empty = error("obstacle=[{shape=\"height_map\", origin=[0.0, 0.0], spacing=[0.1, 0.1], "
                                  "heights=[[0.1, 0.2], [0.1, 0.2]], bottom=0.2}]");
  EXPECT_NE(empty.find("obstacle[0].bottom: the height map is empty"), std::string::npos) << empty;
  const std::string misspelt = error("obstacle=[{shape=\"height_map\", origin=[0.0, 0.0], spacing=[0.1, 0.1], "
                                     "heigths=[[0.1, 0.2], [0.1, 0.2]]}]");
  EXPECT_NE(misspelt.find("obstacle[0].heights: missing"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("heigths"), std::string::npos) << misspelt;
  const std::string both = error("obstacle=[{shape=\"height_map\", heights_file=\"terrain/dem.asc\", "
                                 "heights=[[0.1, 0.2], [0.1, 0.2]]}]");
  EXPECT_NE(both.find("obstacle[0]: give the height map's heights in its heights_file or here, not both"),
            std::string::npos) << both;
  const std::string polygon = error("obstacle=[{shape=\"polygon\", heights_file=\"terrain/dem.asc\"}]");
  EXPECT_NE(polygon.find("obstacle[0].heights_file: used only with shape = \"height_map\""), std::string::npos)
      << polygon;
  const std::string outside = error("obstacle=[{shape=\"height_map\", origin=[5.0, 0.0], spacing=[0.1, 0.1], "
                                    "heights=[[0.1, 0.2], [0.1, 0.2]]}]");
  EXPECT_NE(outside.find("obstacle[0]: the shape within x [4.95, 5.15], y below 0.2, z [-0.05, 0.15] lies outside "
                         "the domain"), std::string::npos) << outside;
  std::string misnamed = refusing;
  misnamed.replace(misnamed.find("refuse"), 6, "smooth");
  const std::string unknown_choice = error(misnamed);
  EXPECT_NE(unknown_choice.find("obstacle[0].thin_ridges"), std::string::npos) << unknown_choice;
  EXPECT_NE(unknown_choice.find("'smooth' is not one of: lower, refuse"), std::string::npos) << unknown_choice;
  const std::string of_soil = error_of(layered, {coupled, "initial.soil=[{shape=\"height_map\", thin_ridges=\"lower\", "
                                       "origin=[0.0, 0.0], spacing=[0.1, 0.1], heights=[[0.1, 0.2], [0.1, 0.2]]}]"}, source);
  EXPECT_NE(of_soil.find("initial.soil[0].thin_ridges: unknown key"), std::string::npos) << of_soil;
  const std::string planar = error_of(two_phase, {"soil.rheology.friction_angle=30", coupled,
                                                  "obstacle=[{shape=\"height_map\", origin=[0.0, 0.0], spacing=[0.1, 0.1], "
                                                  "heights=[[0.1, 0.2], [0.1, 0.2]]}]"});
  EXPECT_NE(planar.find("obstacle[0].shape: a height map is a solid of a mesh of layers"), std::string::npos) << planar;
  fs::remove_all(dir);
}

// A line sample's points have three coordinates on a mesh of layers (a planar one's z is 0).
TEST(CaseFile, AMeshOfLayersReadsLineSamplesOfThreeCoordinates) {
  const CaseConfig c = parse_case(layered, {"output.line=[{name=\"a\", start=[0.0, 0.1, -0.2], end=[0.8, 0.1, 0.2]}]"});
  ASSERT_EQ(c.output.lines.size(), 1u);
  EXPECT_EQ(c.output.lines[0].start, (std::array<double, 3>{0.0, 0.1, -0.2}));
  EXPECT_EQ(c.output.lines[0].end, (std::array<double, 3>{0.8, 0.1, 0.2}));
  EXPECT_EQ(c.output.lines[0].points, 101);
}

// Periodic west and east sides on a mesh of layers, with the planar mesh's rules (cells of one width
// along x, no air band across them).
TEST(CaseFile, AMeshOfLayersMayBePeriodicAlongX) {
  const std::vector<std::string> joined = {"boundary.west={type = \"periodic\"}", "boundary.east={type = \"periodic\"}"};
  const CaseConfig c = parse_case(layered, joined);
  EXPECT_TRUE(c.mesh.periodic_x);
  EXPECT_EQ(c.flow.periodic_ambient_density, 1.0);  // the air's
  std::vector<std::string> graded = joined;
  graded.push_back("mesh.grading=[2.0, 1.0, 1.0]");
  EXPECT_NE(error_of(layered, graded).find("mesh.grading: periodic west and east sides need cells of one width along x"),
            std::string::npos);
  std::vector<std::string> banded = joined;
  banded.insert(banded.end(), {"numerics.pressure_coupling=\"coupled\"", "numerics.air_band=12"});
  EXPECT_NE(error_of(layered, banded).find("numerics.air_band: the air band's region does not reach across periodic sides"),
            std::string::npos);
}

// Soil materials on a mesh of layers: a solid's `material` as a planar shape's, and the shapes laid out
// in the order listed, solids and planar shapes alike, so that the last listed holds a point.
TEST(CaseFile, AMeshOfLayersReadsSoilMaterialsOfSolidsAndShapes) {
  const std::string clay = "soil.materials=[{name = \"clay\", friction_angle = 20.0, density = 1800.0}]";
  const CaseConfig c = parse_case(
      layered, {clay, "initial.soil=[{shape=\"circle\", centre=[0.0, 0.0], radius=0.1}, "
                      "{shape=\"box\", lower=[0.5, 0.0, -0.2], upper=[0.8, 0.1, 0.0], material=\"clay\"}, "
                      "{shape=\"box\", lower=[0.0, 0.0], upper=[0.3, 0.05], material=\"clay\"}, "
                      "{shape=\"sphere\", centre=[0.6, 0.4, 0.1], radius=0.05}]"});
  ASSERT_EQ(c.soil->materials.size(), 1u);
  EXPECT_EQ(c.soil->initial_material, (std::vector<int>{0, 1, 1, 0}));
  EXPECT_EQ(c.soil->initial_shape_is_solid, (std::vector<bool>{false, true, false, true}));
  const auto solids = c.soil->initial_solids(c.mesh.lower[2], c.mesh.upper[2]);
  ASSERT_EQ(solids.size(), 4u);
  EXPECT_TRUE(std::holds_alternative<interface::Extrusion>(solids[0]));
  EXPECT_TRUE(std::holds_alternative<interface::Box3>(solids[1]));
  EXPECT_TRUE(std::holds_alternative<interface::Extrusion>(solids[2]));
  EXPECT_TRUE(std::holds_alternative<interface::Sphere>(solids[3]));
  EXPECT_TRUE(interface::contains(solids[2], 0.25, 0.04, 0.19));  // extruded across the whole depth
  // A solid's material must name one of the case's.
  const std::string e = error_of(layered, {clay, "initial.soil=[{shape=\"sphere\", centre=[0.6, 0.4, 0.1], "
                                                 "radius=0.05, material=\"clya\"}]"});
  EXPECT_NE(e.find("initial.soil[0].material: no soil material named 'clya' (the case's are: clay)"), std::string::npos)
      << e;
}

TEST(CaseFile, AMeshOfLayersRefusesWhatItLacks) {
  const std::pair<std::vector<std::string>, const char*> refused[] = {
      {{"mesh.cells=[8, 6, 1]"}, "one cell along z is a planar mesh"},
      {{"mesh.upper=[0.8, 0.6]"}, "mesh.upper: expected 3 numbers"},
      {{"mesh.grading=[1.0, 2.0]"}, "mesh.grading: expected 3 numbers"},
      {{"mesh.geometry=\"axisymmetric\""}, "an axisymmetric mesh is one layer"},
      {{"physics.gravity=[0.0, -9.81]"}, "physics.gravity: expected 3 numbers"},
      {{"boundary.south={type=\"wall\", velocity=[0.0, 0.1]}"}, "boundary.south.velocity: expected 3 numbers"},
      {{"numerics.pressure_coupling=\"coupled\"", "numerics.air_band=12", "physics.gravity=[0.0, -9.81, 1.0]"},
       "numerics.air_band: needs gravity along y"},
      {{"boundary.back={type=\"wall\", friction_angle=20.0}", "soil.yield_pressure=\"cell\""},
       "boundary.back: a wall's friction (friction_angle, adhesion) needs soil.yield_pressure = \"face\""},
      {{"output.line=[{name=\"a\", start=[0.0, 0.1], end=[0.5, 0.1, 0.0]}]"}, "output.line[0].start: expected 3 numbers"},
      {{"output.line=[{name=\"a\", start=[0.0, 0.1, 0.0], end=[0.5, 0.1, 0.3]}]"},
       "output.line[0].end: [0.5, 0.1, 0.3] lies outside the domain [0, 0.8] x [0, 0.6] x [-0.2, 0.2]"},
      {{"numerics.pressure_coupling=\"coupled\"", "obstacle=[{shape=\"sphere\", centre=[5.0, 5.0, 5.0], radius=0.1}]"},
       "obstacle[0]: the shape within x [4.9, 5.1], y [4.9, 5.1], z [4.9, 5.1] lies outside the domain"},
      {{"obstacle=[{shape=\"box\", lower=[0.0, 0.0, 0.0], upper=[0.1, 0.1, 0.1]}]"},
       "obstacle: needs numerics.pressure_coupling = \"coupled\""},
      {{"initial.soil=[{shape=\"sphere\", centre=[5.0, 5.0, 5.0], radius=0.1}]"}, "lies outside the domain"},
      {{"initial.soil=[{shape=\"cylinder\", centre=[0.1, 0.0], radius=0.1, bottom=0.2, top=0.1}]"}, "the cylinder is empty"},
      {{"initial.soil=[{shape=\"box\", lower=[0.0, 0.0, 0.0], upper=[0.1, 0.1]}]"}, "initial.soil[0].upper: expected 3 numbers"},
  };
  for (const auto& [overrides, message] : refused) {
    const std::string e = error_of(layered, overrides);
    EXPECT_NE(e.find(message), std::string::npos) << overrides.front() << ": " << e;
  }
  // The front and back belong to a mesh of layers; a planar one says so.
  EXPECT_NE(error_of(minimal, {"boundary.front={type=\"wall\"}"}).find("a planar mesh has no front and back sides"),
            std::string::npos);
  // A side missing is named.
  std::string without_back = layered;
  without_back.erase(without_back.find("back = { type = \"wall\" }"));
  EXPECT_NE(error_of(without_back).find("boundary.back: missing"), std::string::npos) << error_of(without_back);
}

}  // namespace
}  // namespace granflow

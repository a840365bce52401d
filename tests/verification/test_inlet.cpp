// Inlets (`type = "inlet"`): a side through which a given velocity enters, carrying soil below a given
// depth and air above it.
// - A channel fed by a uniform inflow, one fluid: downstream the flow is Poiseuille's, u = 6 U y (H - y)
//   / H^2, reached at second order in the cell size (8, 16 and 32 cells across), and what leaves
//   through the open east side is what the inlet lets in, to the solver's tolerance.
// - The momentum an inflow brings: fluid at rest in a periodic strip, fed through its bottom at V
//   with a velocity U along the strip, takes U up with the flow, as u_t + V u_y = nu u_yy with u = U
//   at the inlet (Ogata & Banks' solution); through the top (the high side) alike, mirrored.
// - Soil fed onto a floor through the lower part of the west side, into a domain that starts without
//   soil: the volume in the domain is U d t to round-off, on a planar mesh (d on a cell face, and
//   halfway through a cell, whose ghost holds half of it) and on a mesh of layers; the soil fraction
//   stays within [0, 1]; the history's outflow is minus that volume; the soil entering carries no
//   displacement; a soil material fed alone fills its share.
// - An inlet open over part of its side (span_x, span_y, span_z), a wall at rest elsewhere: the soil
//   let in is U times the open area below the soil depth times t, to round-off, where the opening's
//   ends and the depth cut cells (one face cut by both), through a slot in the top of a planar and of
//   an axisymmetric mesh (the hole's area by r dr) and on a mesh of layers; none enters outside it.
// - Round-off traces of soil in the air of a fed chute do not change the interface Courant number.
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

// A channel H = 1 m high and 4 m long, of a fluid of viscosity 1 Pa s and density 1 kg/m^3, fed at
// U = 1 m/s through the west side: Re = 1, developed within a height of the inlet.
std::string channel_case(int rows) {
  return R"(
[mesh]
cells = [)" + std::to_string(4 * rows) + ", " + std::to_string(rows) + R"(]
upper = [4.0, 1.0]
[time]
end = 20.0
dt = 0.01
courant = 10.0
max_dt = 1.0
steady_tolerance = 1e-10
[fluid]
density = 1.0
viscosity = 1.0
[boundary]
west = { type = "inlet", velocity = [1.0, 0.0] }
east = { type = "atmosphere", pressure_kind = "static" }
south = { type = "wall" }
north = { type = "wall" }
[numerics]
outer_iterations = 2
[solver.pressure]
rtol = 1e-12
[output]
progress_seconds = 0
)";
}

struct Channel {
  double profile_error = 0.0;  // m/s: largest |u - Poiseuille| over the column at x = 3 m
  double outflow = 0.0;        // m^2/s: through the east side (U H = 1 let in)
};

Channel run_channel(int rows) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(channel_case(rows)), "");
  sim.run();
  const Grid& g = sim.grid();
  const auto u = gather_to_root(g, sim.flow().velocity(0));
  Channel out;
  {  // the faces east of the last column, as the ranks that hold it keep them (in the local vectors)
    const ConstFieldArray face(g.field_dm(), sim.flow().face_velocity(0).local());
    const auto& b = g.owned();
    if (b.xe() == g.nx())
      for (int j = b.ys; j < b.ye(); ++j) out.outflow += face[j][g.nx() - 1] * g.dy(j);
    MPI_Allreduce(MPI_IN_PLACE, &out.outflow, 1, MPI_DOUBLE, MPI_SUM, g.comm());
  }
  if (!test::is_root()) return out;
  const int nx = g.nx(), i = 3 * nx / 4;  // the column whose west face is at x = 3 m
  for (int j = 0; j < rows; ++j) {
    const double y = g.yc(j);
    out.profile_error = std::max(out.profile_error, std::abs(u[size_t(j) * nx + i] - 6.0 * y * (1.0 - y)));
  }
  return out;
}

TEST(Inlet, AChannelFedUniformlyDevelopsPoiseuillesFlowAtSecondOrder) {
  const Channel coarse = run_channel(8), medium = run_channel(16), fine = run_channel(32);
  for (const Channel* c : {&coarse, &medium, &fine}) EXPECT_NEAR(c->outflow, 1.0, 1e-9);
  if (!test::is_root()) return;
  std::printf("largest |u - Poiseuille| at x = 3 m: %.3e, %.3e, %.3e m/s on 8, 16, 32 rows (orders %.2f, %.2f); "
              "outflow - inflow %.1e, %.1e, %.1e m^2/s\n",
              coarse.profile_error, medium.profile_error, fine.profile_error,
              std::log2(coarse.profile_error / medium.profile_error),
              std::log2(medium.profile_error / fine.profile_error),
              coarse.outflow - 1.0, medium.outflow - 1.0, fine.outflow - 1.0);
  EXPECT_LT(fine.profile_error, 2e-3);  // measured 1.46e-3 of the centreline's 1.5 m/s
  EXPECT_GT(std::log2(coarse.profile_error / medium.profile_error), 1.8);
  EXPECT_GT(std::log2(medium.profile_error / fine.profile_error), 1.8);
}

// A strip 0.25 m wide (periodic along x) and 1 m high of a fluid of viscosity 1e-3 Pa s, density 1, at
// rest, fed through its bottom (or its top) at V = 0.1 m/s, with U = 1 m/s along the strip; open at
// the other end. The flow stays uniform along x: v = V, and u obeys the advection-diffusion equation.
std::string fed_strip_case(bool from_top, int rows) {
  const std::string inlet = "{ type = \"inlet\", velocity = [1.0, " + std::string(from_top ? "-0.1" : "0.1") + "] }";
  const std::string open = "{ type = \"atmosphere\", pressure_kind = \"static\" }";
  return R"(
[mesh]
cells = [4, )" + std::to_string(rows) + R"(]
upper = [0.25, 1.0]
[time]
end = 4.0
dt = 0.01
adaptive = false
[physics]
gravity = [0.0, 0.0]
[fluid]
density = 1.0
viscosity = 1e-3
[boundary]
west = { type = "periodic" }
east = { type = "periodic" }
south = )" + (from_top ? open : inlet) + R"(
north = )" + (from_top ? inlet : open) + R"(
[numerics]
outer_iterations = 2
[output]
progress_seconds = 0
)";
}

// Ogata & Banks (1961): u_t + V u_y = nu u_yy on y > 0, u = 0 at t = 0 and u = U at y = 0.
double ogata_banks(double y, double t, double speed, double nu) {
  const double s = 2.0 * std::sqrt(nu * t);
  return 0.5 * (std::erfc((y - speed * t) / s) + std::exp(speed * y / nu) * std::erfc((y + speed * t) / s));
}

TEST(Inlet, TheInflowBringsItsMomentumAlongTheSide) {
  const int rows = 100;
  for (bool from_top : {false, true}) {
    Simulation sim(PETSC_COMM_WORLD, parse_case(fed_strip_case(from_top, rows)), "");
    sim.run();
    const Grid& g = sim.grid();
    const auto u = gather_to_root(g, sim.flow().velocity(0)), v = gather_to_root(g, sim.flow().velocity(1));
    if (!test::is_root()) continue;
    double worst = 0.0, worst_v = 0.0, taken_up = 0.0, exact_taken_up = 0.0;
    for (int j = 0; j < rows; ++j) {
      const double distance = from_top ? 1.0 - g.yc(j) : g.yc(j);  // from the inlet
      const double exact = ogata_banks(distance, 4.0, 0.1, 1e-3);
      worst = std::max(worst, std::abs(u[size_t(j) * g.nx() + 1] - exact));
      worst_v = std::max(worst_v, std::abs(std::abs(v[size_t(j) * g.nx() + 1]) - 0.1));
      taken_up += u[size_t(j) * g.nx() + 1] * g.dy(j);
      exact_taken_up += exact * g.dy(j);
    }
    std::printf("fed through the %s: largest |u - Ogata-Banks| %.4f m/s of 1, |v| - V to %.1e; momentum taken "
                "up %.4f against %.4f m^2/s (the front at V t = 0.4 m)\n",
                from_top ? "top" : "bottom", worst, worst_v, taken_up, exact_taken_up);
    // Measured 0.0067 both ways, and 0.4100 taken up of 0.4100; without the inflow's momentum (the wall's
    // viscous pull alone) 0.0176, and 0.4072.
    EXPECT_LT(worst, 0.01);
    EXPECT_NEAR(taken_up, exact_taken_up, 2e-3 * exact_taken_up);
    EXPECT_LT(worst_v, 1e-7);  // the pressure solve's tolerance: measured 3.5e-9 and 4.7e-9
  }
}

// Soil of the Bui et al. collapse fed at U = 0.2 m/s through the west side below depth d onto a floor,
// 5 mm cells, into air under an open top and east side; it has not reached the east side by t = 0.3 s.
std::string soil_inlet_case(double depth, bool layers, const std::string& extra = "") {
  std::string text = test::file_text(test::repo_path("cases/bui2008_experiment.toml"));
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("soil_inlet_case: no '" + from + "' in the case");
    text.replace(at, from.size(), to);
  };
  replace("[[initial.soil]]\nshape = \"box\"\nlower = [0.0, 0.0]\nupper = [0.2, 0.1]\n", "");
  const std::string velocity = layers ? "[0.2, 0.0, 0.0]" : "[0.2, 0.0]";
  replace("west = { type = \"wall\" }", "west = { type = \"inlet\", velocity = " + velocity +
                                            ", soil_fraction = 1.0, soil_depth = " + std::to_string(depth) + extra +
                                            " }");
  if (layers) {
    replace("gravity = [0.0, -9.81]", "gravity = [0.0, -9.81, 0.0]");
    replace("north = { type = \"atmosphere\" }",
            "north = { type = \"atmosphere\" }\nfront = { type = \"wall\" }\nback = { type = \"symmetry\" }");
  }
  return text;
}

struct SoilFed {
  double volume = 0.0, outflow = 0.0, lowest_c = 0.0, highest_c = 0.0, largest_displacement = 0.0;
  std::vector<double> material_volumes;
  double inlet_column_height = 0.0, inlet_column_soil_above = 0.0;  // m: the first column's soil, and above 2 cm
};

SoilFed run_soil_inlet(const std::string& text, bool layers) {
  std::vector<std::string> overrides{"output.progress_seconds=0", "time.end=0.3", "output.interval=0.3"};
  if (layers) overrides.insert(overrides.end(), {"mesh.cells=[40, 10, 4]", "mesh.lower=[0.0, 0.0, 0.0]",
                                                 "mesh.upper=[0.2, 0.05, 0.02]"});
  else overrides.insert(overrides.end(), {"mesh.cells=[40, 10]", "mesh.upper=[0.2, 0.05]"});
  Simulation sim(PETSC_COMM_WORLD, parse_case(text, test::bui2008_at_courant_one(overrides)), "");
  sim.run();
  const SoilBudget b = sim.soil()->budget(sim.flow());
  const auto c = gather_to_root(sim.grid(), sim.soil()->soil_fraction());
  SoilFed out{b.soil_volume, b.soil_outflow, 0.0, 0.0, sim.soil()->largest_displacement(),
              sim.soil()->material_volumes()};
  if (test::is_root()) {
    out.lowest_c = *std::min_element(c.begin(), c.end());
    out.highest_c = *std::max_element(c.begin(), c.end());
    const Grid& g = sim.grid();
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j) {
        const double soil = c[(size_t(k) * g.ny() + j) * g.nx()] * g.dy(j) / g.nz();
        out.inlet_column_height += soil;
        if (g.yc(j) > 0.02) out.inlet_column_soil_above += soil;
      }
  }
  return out;
}

TEST(Inlet, SoilFedThroughTheLowerPartOfASideFillsAtItsRate) {
  const double depth = 0.01, t = 0.3, speed = 0.2;
  const SoilFed on_face = run_soil_inlet(soil_inlet_case(depth, false), false);
  const SoilFed half_cell = run_soil_inlet(soil_inlet_case(0.0125, false), false);
  const double exact = speed * depth * t, exact_half = speed * 0.0125 * t;  // m^3 per metre of depth
  if (test::is_root())
    std::printf("soil let in: %.15g and %.15g m^2 against %.15g and %.15g; outflow %.3g, %.3g; c in [%.2g, "
              "1 + %.2g]; largest displacement %.3g m\n",
              on_face.volume, half_cell.volume, exact, exact_half, on_face.outflow, half_cell.outflow,
              on_face.lowest_c, on_face.highest_c - 1.0, on_face.largest_displacement);
  EXPECT_NEAR(on_face.volume / exact, 1.0, 1e-12);
  EXPECT_NEAR(half_cell.volume / exact_half, 1.0, 1e-12);
  EXPECT_NEAR(on_face.outflow / exact, -1.0, 1e-12);
  EXPECT_NEAR(half_cell.outflow / exact_half, -1.0, 1e-12);
  if (test::is_root()) {
    // The soil enters below its depth, from the floor: the first column holds about d, none above 2 cm.
    std::printf("the inlet's column: %.4f and %.4f m of soil, %.1e and %.1e above 2 cm\n",
                on_face.inlet_column_height, half_cell.inlet_column_height, on_face.inlet_column_soil_above,
                half_cell.inlet_column_soil_above);
    EXPECT_NEAR(on_face.inlet_column_height, 1.15 * depth, 0.25 * depth);  // measured 1.10 d
    EXPECT_NEAR(half_cell.inlet_column_height, 1.15 * 0.0125, 0.25 * 0.0125);  // 1.06 d
    EXPECT_LT(on_face.inlet_column_soil_above, 1e-6);
    EXPECT_GE(on_face.lowest_c, -1e-12);
    EXPECT_LE(on_face.highest_c, 1.0 + 1e-12);
    EXPECT_GE(half_cell.lowest_c, -1e-12);
    EXPECT_LE(half_cell.highest_c, 1.0 + 1e-12);
  }
  // Soil enters undisplaced; it has moved at most U t = 6 cm since, less where the floor holds it.
  EXPECT_GT(on_face.largest_displacement, 0.0);
  EXPECT_LT(on_face.largest_displacement, speed * t * 1.2);
}

TEST(Inlet, SoilFedOnAMeshOfLayersFillsAtItsRate) {
  const double depth = 0.01, t = 0.3, speed = 0.2, width = 0.02;
  const SoilFed fed = run_soil_inlet(soil_inlet_case(depth, true), true);
  const double exact = speed * depth * width * t;
  if (test::is_root())
    std::printf("soil let in on a mesh of layers: %.15g m^3 against %.15g; c in [%.2g, 1 + %.2g]\n", fed.volume, exact,
              fed.lowest_c, fed.highest_c - 1.0);
  EXPECT_NEAR(fed.volume / exact, 1.0, 1e-12);
  EXPECT_NEAR(fed.outflow / exact, -1.0, 1e-12);
  if (test::is_root()) {
    EXPECT_GE(fed.lowest_c, -1e-12);
    EXPECT_LE(fed.highest_c, 1.0 + 1e-12);
    EXPECT_NEAR(fed.inlet_column_height, 1.15 * depth, 0.25 * depth);  // the mean over the layers: 1.20 d
    EXPECT_LT(fed.inlet_column_soil_above, 1e-6);
  }
}

// An inlet's schedule (`schedule`): the soil let in is U d times the integral of the factor. Fed for
// 0.2 s and then closed, or at half the velocity throughout, exactly: the faces a step's solve leaves
// carry the inflow over the next step's sweeps, and steps land on the schedule's times. Across a ramp
// the factor is taken in the middle of the next step, as long as the last: -0.08 % (at each step's
// end, first order in the step, it was -4.35 %).
TEST(Inlet, AScheduledInflowLetsInItsVolume) {
  const double depth = 0.01, speed = 0.2;
  const SoilFed stopped =
      run_soil_inlet(soil_inlet_case(depth, false, ", schedule = [[0.0, 1.0], [0.2, 1.0], [0.2, 0.0]]"), false);
  const SoilFed half = run_soil_inlet(soil_inlet_case(depth, false, ", schedule = [[0.0, 0.5]]"), false);
  const SoilFed ramp = run_soil_inlet(soil_inlet_case(depth, false, ", schedule = [[0.0, 0.0], [0.3, 1.0]]"), false);
  const double closed = speed * depth * 0.2, at_half = speed * depth * 0.3 * 0.5, ramped = speed * depth * 0.15;
  if (test::is_root())
    std::printf("soil let in: closed at 0.2 s %.15g against %.15g; at half the velocity %.15g against %.15g; "
                "ramped from 0 to 1 over 0.3 s %.6g against %.6g (%+.2f %%)\n",
                stopped.volume, closed, half.volume, at_half, ramp.volume, ramped,
                100.0 * (ramp.volume / ramped - 1.0));
  EXPECT_NEAR(stopped.volume / closed, 1.0, 1e-12);
  EXPECT_NEAR(stopped.outflow / closed, -1.0, 1e-12);
  EXPECT_NEAR(half.volume / at_half, 1.0, 1e-12);
  EXPECT_NEAR(ramp.volume / ramped, 1.0, 5e-3);
}

// Fed for 0.1 s, closed until 0.5 s and opened again: the soil that came in first comes to rest while
// the inlet is closed (at t = 0.29 s, where a run without the reopening stops), but a run told to stop
// at rest (time.rest_speed) goes on while the schedule has a change to come.
TEST(Inlet, ARunDoesNotStopAtRestBeforeItsScheduleEnds) {
  const std::string text =
      soil_inlet_case(0.01, false, ", schedule = [[0.0, 1.0], [0.1, 1.0], [0.1, 0.0], [0.5, 0.0], [0.5, 1.0]]");
  Simulation sim(PETSC_COMM_WORLD,
                 parse_case(text, {"output.progress_seconds=0", "time.end=0.6", "output.interval=0.6",
                                   "mesh.cells=[40, 10]", "mesh.upper=[0.2, 0.05]", "time.rest_speed=1e-3"}),
                 "");
  const RunSummary s = sim.run();
  const double volume = sim.soil()->budget(sim.flow()).soil_volume, exact = 0.2 * 0.01 * (0.1 + (s.time - 0.5));
  if (test::is_root())
    std::printf("stopped at t = %.4g s (at rest: %s), soil let in %.15g against %.15g\n", s.time,
                s.soil_at_rest ? "yes" : "no", volume, exact);
  EXPECT_GT(s.time, 0.5);
  EXPECT_NEAR(volume / exact, 1.0, 1e-12);
}

// The soil let in is `exact` to round-off, the history's outflow minus it, and c stays within [0, 1].
void expect_let_in(const SoilFed& fed, double exact) {
  EXPECT_NEAR(fed.volume / exact, 1.0, 1e-12);
  EXPECT_NEAR(fed.outflow / exact, -1.0, 1e-12);
  if (test::is_root()) {
    EXPECT_GE(fed.lowest_c, -1e-12);
    EXPECT_LE(fed.highest_c, 1.0 + 1e-12);
  }
}

// Soil fed through the west side between span_y[0] and the soil depth, air above it up to span_y[1]: U
// (d - y0) t. The opening's low end cuts a cell and the depth another, or both cut one face.
TEST(Inlet, SoilFedThroughPartOfASideFillsAtItsRate) {
  const double speed = 0.2, t = 0.3;
  const SoilFed apart = run_soil_inlet(soil_inlet_case(0.0175, false, ", span_y = [0.0075, 0.03]"), false);
  const SoilFed one_face = run_soil_inlet(soil_inlet_case(0.014, false, ", span_y = [0.0125, 0.03]"), false);
  const double exact_apart = speed * (0.0175 - 0.0075) * t, exact_one_face = speed * (0.014 - 0.0125) * t;
  if (test::is_root())
    std::printf("soil let in through part of the side: %.15g and %.15g m^2 against %.15g and %.15g; c in [%.2g, "
                "1 + %.2g]\n", apart.volume, one_face.volume, exact_apart, exact_one_face, apart.lowest_c,
                apart.highest_c - 1.0);
  expect_let_in(apart, exact_apart);
  expect_let_in(one_face, exact_one_face);
}

// Soil poured at 0.2 m/s through a slot in the top (a wall elsewhere) onto the floor 5 cm below, the air
// leaving through the open east side; on an axisymmetric mesh a hole about the axis.
SoilFed run_slot(const std::string& span, bool axisymmetric) {
  std::string text = soil_inlet_case(0.01, false);
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("run_slot: no '" + from + "' in the case");
    text.replace(at, from.size(), to);
  };
  replace("north = { type = \"atmosphere\" }", "north = { type = \"inlet\", velocity = [0.0, -0.2], soil_fraction "
                                               "= 1.0, span_x = " + span + " }");
  const size_t west = text.find("west = {");
  text.replace(west, text.find('}', west) + 1 - west,
               axisymmetric ? "west = { type = \"axis\" }" : "west = { type = \"wall\" }");
  if (axisymmetric) replace("[mesh]", "[mesh]\ngeometry = \"axisymmetric\"");
  return run_soil_inlet(text, false);
}

TEST(Inlet, SoilPouredThroughASlotInTheTopFillsAtItsRate) {
  const double speed = 0.2, t = 0.3;
  const SoilFed slot = run_slot("[0.0725, 0.1075]", false);
  const SoilFed hole = run_slot("[-1.0, 0.0125]", true);
  const double exact_slot = speed * 0.035 * t, exact_hole = speed * 0.5 * 0.0125 * 0.0125 * t;  // per radian
  if (test::is_root())
    std::printf("soil poured through a slot: %.15g m^2 against %.15g; through a hole about the axis %.15g m^3/rad "
                "against %.15g; c in [%.2g, 1 + %.2g]\n", slot.volume, exact_slot, hole.volume, exact_hole,
                slot.lowest_c, slot.highest_c - 1.0);
  expect_let_in(slot, exact_slot);
  expect_let_in(hole, exact_hole);
}

// On a mesh of layers 2 cm deep: soil from 2.5 mm to the depth of 1 cm, in the front 1.25 cm.
TEST(Inlet, SoilFedThroughPartOfASideOfAMeshOfLayersFillsAtItsRate) {
  const double speed = 0.2, t = 0.3;
  const SoilFed fed =
      run_soil_inlet(soil_inlet_case(0.01, true, ", span_y = [0.0025, 0.05], span_z = [-1.0, 0.0125]"), true);
  const double exact = speed * (0.01 - 0.0025) * 0.0125 * t;
  if (test::is_root())
    std::printf("soil let in through part of a side of a mesh of layers: %.15g m^3 against %.15g\n", fed.volume,
                exact);
  expect_let_in(fed, exact);
}

TEST(Inlet, ASoilMaterialFedAloneFillsItsShare) {
  std::string text = soil_inlet_case(0.01, false, ", material = \"weak\"");
  const std::string materials = "[[soil.materials]]\nname = \"weak\"\nfriction_angle = 10.0\n\n[mixture]";
  text.replace(text.find("[mixture]"), 9, materials);
  const SoilFed fed = run_soil_inlet(text, false);
  const double exact = 0.2 * 0.01 * 0.3;
  ASSERT_EQ(fed.material_volumes.size(), 2u);
  if (test::is_root())
    std::printf("soil let in: %.15g m^2, of which the rheology's own %.3g and 'weak' %.15g\n", fed.volume,
                fed.material_volumes[0], fed.material_volumes[1]);
  EXPECT_NEAR(fed.material_volumes[1] / exact, 1.0, 1e-12);
  EXPECT_NEAR(fed.material_volumes[0] / exact, 0.0, 1e-12);
}

// Soil of at most 1e-15 of a cell is round-off: present in air cells on one rank layout and exactly 0
// on another, it must not size the step (each advection clears it, below; a checkpoint of an older run
// may hold it). In the fed chute, whose air over the front runs faster than
// the soil, counting it made the interface Courant number, and the step, jump by 1.6 % between one
// and two ranks. Traces of 1e-16 in every empty cell leave the number as it is; traces of 1e-13,
// soil the sweeps carry, widen the region to the air beside them.
TEST(Inlet, RoundOffTracesOfSoilInTheAirDoNotSizeTheStep) {
  Simulation sim(PETSC_COMM_WORLD,
                 load_case(test::repo_path("cases/chute_inlet.toml"),
                           {"mesh.cells=[100,15]", "time.end=0.15", "output.progress_seconds=0", "output.line=[]"}),
                 "");
  sim.run();
  SoilPhase& soil = *sim.soil();
  const double dt = 1e-3, clean = soil.interface_courant(sim.flow(), dt, 2);
  const Grid& g = sim.grid();
  Field& c = soil.soil_fraction();
  auto replace = [&](double from, double to) {  // in every owned cell that holds `from`
    {
      FieldArray a(g.field_dm(), c.global());
      const CellBox& b = g.owned();
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          if (a.data()[j][i] == from) a.data()[j][i] = to;
    }
    c.scatter_to_local();
  };
  auto with_traces = [&](double trace) {
    const std::vector<double> kept = gather_to_root(g, c);
    replace(0.0, trace);
    const double co = soil.interface_courant(sim.flow(), dt, 2);
    replace(trace, 0.0);  // back as it was
    EXPECT_EQ(gather_to_root(g, c), kept);
    return co;
  };
  const double round_off = with_traces(1e-16), carried = with_traces(1e-13);
  if (test::is_root())
    std::printf("interface Courant number for dt = 1 ms: %.10g; with round-off traces in the air %.10g; with traces "
                "of 1e-13 %.10g\n", clean, round_off, carried);
  EXPECT_GT(clean, 0.1);
  EXPECT_EQ(round_off, clean);
  EXPECT_GT(carried, 1.01 * clean);  // the region reaches faster air
}

// Each advection clears the round-off soil it finds or leaves (interface::round_off_soil), so that "any
// soil" is the same region on every rank layout. Traces of +-1e-16 put in every empty cell of the fed
// chute (planar) and of a mesh of layers fed through its side are gone after one advection, and the
// soil the run had, moved by the sweeps, is all still there.
TEST(Inlet, AnAdvectionClearsTheRoundOffSoilItFinds) {
  auto check = [](const std::string& text, const std::vector<std::string>& overrides, const char* what) {
    Simulation sim(PETSC_COMM_WORLD, parse_case(text, overrides), "");
    sim.run();
    SoilPhase& soil = *sim.soil();
    const Grid& g = sim.grid();
    Field& c = soil.soil_fraction();
    const double volume = soil.budget(sim.flow()).soil_volume;
    double traces = 0.0;  // cells given one
    {
      FieldArray a(g.field_dm(), c.global());
      const CellBox& b = g.owned();
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i)
            if (a.volume()[k][j][i] == 0.0) {
              a.volume()[k][j][i] = (i + j + k) % 2 == 0 ? 1e-16 : -1e-16;
              traces += 1.0;
            }
    }
    c.scatter_to_local();
    MPI_Allreduce(MPI_IN_PLACE, &traces, 1, MPI_DOUBLE, MPI_SUM, g.comm());
    const double outflow = soil.budget(sim.flow()).soil_outflow;
    soil.advect(sim.flow(), 1e-3);
    const SoilBudget after = soil.budget(sim.flow());
    const std::vector<double> all = gather_to_root(g, c);
    if (!test::is_root()) return;
    const auto left = std::count_if(all.begin(), all.end(), [](double v) {
      return v != 0.0 && std::abs(v) <= interface::round_off_soil;
    });
    const double kept = after.soil_volume + (after.soil_outflow - outflow);
    std::printf("%s: %.0f cells given traces of +-1e-16, %ld left with round-off soil after an advection; soil "
                "volume %.15g m^3 (with what left) against %.15g before\n",
                what, traces, long(left), kept, volume);
    EXPECT_GT(traces, 100.0);
    EXPECT_EQ(left, 0);
    EXPECT_NEAR(kept / volume, 1.0, 1e-13);
  };
  check(test::file_text(test::repo_path("cases/chute_inlet.toml")),
        {"mesh.cells=[100,15]", "time.end=0.05", "output.progress_seconds=0", "output.line=[]"}, "fed chute");
  check(soil_inlet_case(0.01, true),
        {"output.progress_seconds=0", "time.end=0.05", "output.interval=0.05", "mesh.cells=[40, 10, 4]",
         "mesh.lower=[0.0, 0.0, 0.0]", "mesh.upper=[0.2, 0.05, 0.02]"},
        "mesh of layers");
}

}  // namespace
}  // namespace granflow

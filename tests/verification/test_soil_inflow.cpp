// Soil entering through an open side (an atmosphere side's inflow_soil_fraction). A channel 1 m long
// between slip walls, without gravity, holds a slug of water 0.1 m long at its west end; the west side
// is open at a static pressure 20 Pa above the east's and lets in water (c = 1). The water and the air
// move as one plug, so its speed obeys
//   (rho_w (L0 + s) + rho_a (L - L0 - s)) dv/dt = dp,   ds/dt = v,
// with s the length of water that entered (the momentum the inflow brings in is what its mass
// gains). Measured: the water let in (the soil's volume in the domain and the history's outflow, which
// is negative for an inflow) is conserved to round-off, and s at t = 0.5 s converges on the
// plug's to first order in the step (backward Euler): 0.023638 and 0.023818 m against 0.023865 m with
// steps of at most 5 and 1 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "solver/simulation.hpp"

namespace granflow {
namespace {

constexpr double height = 0.1, slug = 0.1, length = 1.0, pressure_drop = 20.0;
constexpr double rho_w = 1000.0, rho_a = 1.0, end_time = 0.5;

std::string channel_case(double max_dt) {
  return R"(
[mesh]
cells = [50, 5]
upper = [1.0, 0.1]
[time]
end = 0.5
dt = 1e-3
courant = 0.5
max_dt = )" + std::to_string(max_dt) +
         R"(
[physics]
gravity = [0.0, 0.0]
[air]
density = 1.0
viscosity = 1.8e-5
[soil]
density = 1000.0
viscosity = 1e-3
[mixture]
density = "linear"
viscosity = "linear"
[[initial.soil]]
shape = "box"
lower = [0.0, 0.0]
upper = [0.1, 0.1]
[boundary]
west = { type = "atmosphere", pressure = 20.0, pressure_kind = "static", inflow_soil_fraction = 1.0 }
east = { type = "atmosphere", pressure = 0.0, pressure_kind = "static" }
south = { type = "slip" }
north = { type = "slip" }
[output]
progress_seconds = 0
)";
}

// The length of water the plug above lets in by t = end_time (explicit steps of 1 microsecond).
double plug_inflow() {
  double s = 0.0, v = 0.0;
  const double dt = 1e-6;
  for (long n = 0; n < long(std::llround(end_time / dt)); ++n) {
    v += dt * pressure_drop / (rho_w * (slug + s) + rho_a * (length - slug - s));
    s += dt * v;
  }
  return s;
}

struct Inflow {
  double let_in;       // m: the soil volume gained, over the channel's height
  double conserved;    // (volume now + outflow - initial volume) / initial volume
};

Inflow run_channel(double max_dt) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(channel_case(max_dt)), "");
  sim.run();
  const SoilBudget b = sim.soil()->budget(sim.flow());
  const double initial = slug * height;
  return {(b.soil_volume - initial) / height, (b.soil_volume + b.soil_outflow - initial) / initial};
}

TEST(SoilInflow, ThroughAnOpenSideConservedAndAsFastAsThePlug) {
  const double exact = plug_inflow();
  const Inflow coarse = run_channel(5e-3), fine = run_channel(1e-3);
  std::printf("water let in by t = %.1f s: %.6f m (steps <= 5 ms), %.6f m (<= 1 ms), plug %.6f m; "
              "volume with the outflow conserved to %.1e, %.1e\n",
              end_time, coarse.let_in, fine.let_in, exact, coarse.conserved, fine.conserved);
  EXPECT_NEAR(coarse.conserved, 0.0, 1e-12);
  EXPECT_NEAR(fine.conserved, 0.0, 1e-12);
  EXPECT_GT(fine.let_in, 0.2 * slug);  // water did come in: a fifth of the slug
  EXPECT_NEAR(fine.let_in, exact, 3e-3 * exact);  // measured 1.9e-3
  // First order in the step: five times shorter steps, some five times smaller an error.
  EXPECT_GT(std::abs(coarse.let_in - exact) / std::abs(fine.let_in - exact), 3.0);
}

}  // namespace
}  // namespace granflow

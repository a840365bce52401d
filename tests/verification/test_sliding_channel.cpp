// A layer sliding down a channel between two side walls, on a mesh of layers: the drag of the side
// walls, which a planar mesh cannot have. A layer of depth h over the whole length of a bed at angle
// theta, in a channel of width W, slides as a plug where the bed and the walls are smoother than the
// soil. Its pressure is the weight normal to the bed, p = rho g cos(theta) (h - y), on the bed and on
// the walls alike; so the bed's shear stress is tan(delta_b) rho g cos(theta) h, each wall's shear
// force per length tan(delta_w) rho g cos(theta) h^2 / 2, and the plug accelerates at
//   g (sin(theta) - (tan(delta_b) + tan(delta_w) h / W) cos(theta)),
// the side-wall friction of depth-averaged channel flows (as in Jop, Forterre & Pouliquen 2005's
// mu_w h / W). Between slip walls the layer is the planar one. Where the walls and the bed together
// are stronger than the slope, tan(theta) < tan(delta_b) + tan(delta_w) h / W, the layer stands, as
// side walls hold a heap steeper than its own angle (Jop et al.'s flows on a heap).
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double g = 9.81, degree = std::numbers::pi / 180.0;
constexpr double depth = 0.01, width = 0.02, cell = 0.005;

struct ChannelResult {
  double time = 0.0, mean_velocity = 0.0;  // of the soil
  std::array<double, 3> bed{}, front{};    // the forces of the flow on the bed and on the front wall, N
};

// The shipped Bui et al. case's soil on a bed of friction angle delta_b tilted by theta, the channel's
// front and back sides `side_walls`; to t = 0.1 s with converged outer iterations. A periodic strip four
// cells long (the layer has no ends), the layer two cells deep and four wide. With the linear density
// mixture: the arctan mixture puts nearly the soil's density in a half-filled top cell, and the walls'
// pressure, which grows with the square of the depth, with it (on 4 mm cells, open at both ends, the
// walls took 18 % more than h / W said).
ChannelResult slide_in_channel(double theta, double delta_b, const std::string& side_walls) {
  const double length = 4 * cell;
  const std::vector<std::string> overrides = {
      fmt::format("mesh.cells=[4, {}, {}]", std::lround(0.04 / cell), std::lround(width / cell)),
      "mesh.lower=[0, 0, 0]", fmt::format("mesh.upper=[{}, 0.04, {}]", length, width), "time.end=0.1",
      "output.interval=0.1",
      fmt::format("physics.gravity=[{:.17g}, {:.17g}, 0]", g * std::sin(theta), -g * std::cos(theta)),
      fmt::format("initial.soil=[{{shape = \"box\", lower = [0, 0, 0], upper = [{}, {}, {}]}}]", length, depth, width),
      fmt::format("boundary={{west={{type=\"periodic\"}}, east={{type=\"periodic\"}}, north={{type=\"atmosphere\"}}, "
                  "south={{type=\"wall\", friction_angle={}}}, front={}, back={}}}",
                  delta_b, side_walls, side_walls),
      "mixture.density=\"linear\"", "numerics.air_band=0", "numerics.outer_iterations=10",
      "numerics.outer_tolerance=1e-6", "output.progress_seconds=0"};
  Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(overrides), "");
  sim.run();
  const Grid& grid = sim.grid();
  const auto c = gather_to_root(grid, sim.soil()->soil_fraction());
  const auto u = gather_to_root(grid, sim.flow().velocity(0));
  ChannelResult r;
  r.time = sim.time();
  const auto force = sim.flow().side_forces();
  r.bed = force[int(Side::south)];
  r.front = force[int(Side::front)];
  if (!test::is_root()) return r;
  double volume = 0.0, momentum = 0.0;
  for (int k = 0; k < grid.nz(); ++k)
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) {
        const size_t n = (size_t(k) * grid.ny() + j) * grid.nx() + i;
        volume += c[n] * grid.volume(i, j, k);
        momentum += c[n] * u[n] * grid.volume(i, j, k);
      }
  r.mean_velocity = momentum / volume;
  return r;
}

// 25 deg on a bed of 10 deg, h / W = 1/2: between slip walls the plug accelerates at g (sin theta -
// tan 10 deg cos theta); between walls of 10 deg their drag takes tan(10 deg) / 2 off that. At 13.5
// deg the layer slides between slip walls and stands between walls of 10 deg: tan 13.5 deg = 0.240
// lies between the bed's 0.176 and the bed's and walls' 0.264. Measured to t = 0.1 s: at 25 deg 2.5695
// against 2.5782 m/s^2 between slip walls, 1.7810 against 1.7943 between walls of 10 deg, the walls'
// shear over their normal force 0.1763, the bed's 0.1766; at 13.5 deg 0.5999 against 0.6081 between
// slip walls and 9.4e-7 m/s^2 between walls of 10 deg. Open at both ends on 4 mm cells (100 x 10 x 5,
// 0.4 m long) instead: 2.5519 and 1.7571 (the plug's ends hold it back a little).
TEST(SlidingChannel, SideWallsOfTheirOwnFrictionDragTheLayerByTheirFrictionTimesDepthOverWidth) {
  const double delta_b = 10.0, delta_w = 10.0;
  const double tan_b = std::tan(delta_b * degree), tan_w = std::tan(delta_w * degree);
  const std::string slip = "{type=\"slip\"}", walls = fmt::format("{{type=\"wall\", friction_angle={}}}", delta_w);
  for (const double theta_deg : {25.0, 13.5}) {
    const double theta = theta_deg * degree;
    const ChannelResult free_run = slide_in_channel(theta, delta_b, slip);
    const ChannelResult held = slide_in_channel(theta, delta_b, walls);
    if (!test::is_root()) continue;
    const double free_plug = g * (std::sin(theta) - tan_b * std::cos(theta));
    const double dragged = std::max(0.0, g * (std::sin(theta) - (tan_b + tan_w * depth / width) * std::cos(theta)));
    const double free_a = free_run.mean_velocity / free_run.time, held_a = held.mean_velocity / held.time;
    std::printf("layer at %g deg on a bed of 10 deg to t = %.3f s, mean acceleration: between slip walls %.5g m/s^2 "
                "(plug %.5g), between walls of 10 deg %.5g (plug %.5g); the bed's shear / normal force %.4f, %.4f; "
                "the front wall's %.4f (tan 10 deg = %.4f)\n",
                theta_deg, free_run.time, free_a, free_plug, held_a, dragged, -free_run.bed[0] / free_run.bed[1],
                -held.bed[0] / held.bed[1], held.front[0] / -held.front[2], tan_w);
    EXPECT_NEAR(free_a / free_plug, 1.0, 0.02) << theta_deg;
    EXPECT_NEAR(-free_run.bed[0] / free_run.bed[1] / tan_b, 1.0, 0.01) << theta_deg;
    EXPECT_LT(std::abs(free_run.front[0]), 1e-12) << theta_deg;  // a slip wall takes no shear
    if (dragged == 0.0) {  // the walls hold it
      EXPECT_LT(std::abs(held.mean_velocity), 1e-4 * g * std::sin(theta) * held.time) << theta_deg;
      continue;
    }
    EXPECT_NEAR(held_a / dragged, 1.0, 0.02) << theta_deg;
    EXPECT_NEAR((free_a - held_a) / (free_plug - dragged), 1.0, 0.03) << theta_deg;  // the walls' own share
    EXPECT_NEAR(-held.bed[0] / held.bed[1] / tan_b, 1.0, 0.01) << theta_deg;
    EXPECT_NEAR(held.front[0] / -held.front[2] / tan_w, 1.0, 0.02) << theta_deg;
  }
}

}  // namespace
}  // namespace granflow

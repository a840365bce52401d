// A layer sliding down a channel between two side walls, on a mesh of layers: the drag of the side
// walls, which a planar mesh cannot have. A layer of depth h over the whole length of a bed at angle
// theta, in a channel of width W, slides as a plug where the bed and the walls are smoother than the
// soil. Its pressure is the weight normal to the bed, p = rho g cos(theta) (h - y), on the bed and on
// the walls alike; so the bed's shear stress is tan(delta_b) rho g cos(theta) h, each wall's shear
// force per length tan(delta_w) rho g cos(theta) h^2 / 2, and the plug accelerates at
//   g (sin(theta) - (tan(delta_b) + tan(delta_w) h / W) cos(theta)),
// the side-wall friction of depth-averaged channel flows (as in Jop, Forterre & Pouliquen 2005's
// mu_w h / W). Between slip walls the layer is the planar one.
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
constexpr double length = 0.4, depth = 0.01, width = 0.02, cell = 0.005;

struct ChannelResult {
  double time = 0.0, mean_velocity = 0.0;  // of the soil in the middle fifth of the bed
  std::array<double, 3> bed{}, front{};    // the forces of the flow on the bed and on the front wall, N
};

// The shipped Bui et al. case's soil on a bed of friction angle delta_b tilted by theta, the channel's
// front and back sides `side_walls`; to t = 0.1 s with converged outer iterations. With the linear
// density mixture: the arctan mixture puts nearly the soil's density in the half-filled top cell, so
// that the layer weighs as one 1.75 mm deeper (13 % more mass), and the walls' pressure, which grows
// with the square of the depth, 30 % more (measured: the walls took 18 % more than h / W said).
ChannelResult slide_in_channel(double theta, double delta_b, const std::string& side_walls) {
  const std::vector<std::string> overrides = {
      fmt::format("mesh.cells=[{}, {}, {}]", std::lround(length / cell), std::lround(0.04 / cell),
                  std::lround(width / cell)),
      "mesh.lower=[0, 0, 0]", fmt::format("mesh.upper=[{}, 0.04, {}]", length, width), "time.end=0.1",
      "output.interval=0.1",
      fmt::format("physics.gravity=[{:.17g}, {:.17g}, 0]", g * std::sin(theta), -g * std::cos(theta)),
      fmt::format("initial.soil=[{{shape = \"box\", lower = [0, 0, 0], upper = [{}, {}, {}]}}]", length, depth, width),
      fmt::format("boundary={{west={{type=\"atmosphere\"}}, east={{type=\"atmosphere\"}}, north={{type=\"atmosphere\"}}, "
                  "south={{type=\"wall\", friction_angle={}}}, front={}, back={}}}",
                  delta_b, side_walls, side_walls),
      "mixture.density=\"linear\"", "numerics.air_band=0", "numerics.outer_iterations=10",
      "numerics.outer_tolerance=1e-6",
      "output.progress_seconds=0"};
  Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path("cases/bui2008_experiment.toml"), overrides), "");
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
      for (int i = 0; i < grid.nx(); ++i)
        if (grid.xc(i) > 0.4 * length && grid.xc(i) < 0.6 * length) {
          const size_t n = (size_t(k) * grid.ny() + j) * grid.nx() + i;
          volume += c[n] * grid.volume(i, j, k);
          momentum += c[n] * u[n] * grid.volume(i, j, k);
        }
  r.mean_velocity = momentum / volume;
  return r;
}

// 25 deg on a bed of 10 deg, cells of 5 mm (the layer two deep, four wide), h / W = 1/2. Between slip
// walls the plug accelerates as the planar layer of
// SlidingLayer.OnABedOfItsOwnFrictionSlidesAsAPlugAtThatFriction; between walls of 10 deg the walls'
// drag takes tan(10 deg) / 2 off the friction. Measured to t = 0.1 s: 2.5547 against 2.5782 m/s^2
// between slip walls, 1.7836 against 1.7943 between walls of 10 deg; the walls' shear over their
// normal force 0.1765, the bed's 0.1761 (tan 10 deg = 0.1763). With 4 mm cells (the top cell half
// full): 2.5519 and 1.7571, the walls' ratio 0.1751.
TEST(SlidingChannel, SideWallsOfTheirOwnFrictionDragTheLayerByTheirFrictionTimesDepthOverWidth) {
  const double theta = 25.0 * degree, delta_b = 10.0, delta_w = 10.0;
  const ChannelResult slip = slide_in_channel(theta, delta_b, "{type=\"slip\"}");
  const ChannelResult walls = slide_in_channel(theta, delta_b, fmt::format("{{type=\"wall\", friction_angle={}}}", delta_w));
  if (!test::is_root()) return;
  const double tan_b = std::tan(delta_b * degree), tan_w = std::tan(delta_w * degree);
  const double free_plug = g * (std::sin(theta) - tan_b * std::cos(theta));
  const double dragged = g * (std::sin(theta) - (tan_b + tan_w * depth / width) * std::cos(theta));
  const double slip_a = slip.mean_velocity / slip.time, walls_a = walls.mean_velocity / walls.time;
  std::printf("layer at 25 deg on a bed of 10 deg to t = %.3f s, mean acceleration of its middle: between slip walls "
              "%.5g m/s^2 (plug %.5g), between walls of 10 deg %.5g (plug %.5g); the bed's shear / normal force %.4f, "
              "%.4f; the front wall's %.4f (tan 10 deg = %.4f)\n",
              slip.time, slip_a, free_plug, walls_a, dragged, -slip.bed[0] / slip.bed[1], -walls.bed[0] / walls.bed[1],
              walls.front[0] / -walls.front[2], tan_w);
  EXPECT_NEAR(slip_a / free_plug, 1.0, 0.025);
  EXPECT_NEAR(walls_a / dragged, 1.0, 0.025);
  EXPECT_NEAR((slip_a - walls_a) / (free_plug - dragged), 1.0, 0.05);  // the walls' own share
  EXPECT_NEAR(-walls.bed[0] / walls.bed[1] / tan_b, 1.0, 0.01);
  EXPECT_NEAR(walls.front[0] / -walls.front[2] / tan_w, 1.0, 0.02);
  EXPECT_LT(std::abs(slip.front[0]), 1e-12);  // a slip wall takes no shear
}

}  // namespace
}  // namespace granflow

// The solver's own advection of the soil fraction (SoilPhase::advect: the distributed fields, their
// ghosts and boundaries, the dilatation indicator and the alternating sweeps) against the advection
// tests' serial driver (SerialVofField), which the scheme's accuracy tests use: a disc turned by a
// solid-body rotation, from the same initial fractions and face velocities, must end the same (to the
// bit, measured on 1, 2 and 3 ranks; asserted to 1e-12), on one rank and on two (tests/parallel.cmake).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "io/case_file.hpp"
#include "mesh/gather.hpp"
#include "serial_vof_field.hpp"
#include "solver/simulation.hpp"

namespace granflow {
namespace {

constexpr int cells = 64;
constexpr double omega = 1.0;  // rad/s about (0.5, 0.5)
double psi(double x, double y) { return -0.5 * omega * ((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)); }

constexpr const char* disc_case = R"(
[mesh]
cells = [64, 64]
upper = [1.0, 1.0]
[time]
end = 1.0
dt = 1e-3
adaptive = false
[air]
density = 1.0
viscosity = 1e-5
[soil]
density = 1000.0
viscosity = 1e-3
[[initial.soil]]
shape = "circle"
centre = [0.5, 0.72]
radius = 0.15
[[initial.soil]]
shape = "box"
lower = [0.62, 0.45]
upper = [0.7, 0.6]
[boundary]
west = { type = "slip" }
east = { type = "slip" }
south = { type = "slip" }
north = { type = "slip" }
[output]
fields = false
progress_seconds = 0
)";

TEST(ProductionAdvection, MatchesTheSerialDriverToRoundOff) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(disc_case), "");
  const Grid& grid = sim.grid();
  FlowSolver& flow = sim.flow();
  SoilPhase& soil = *sim.soil();
  // Face velocities from psi at the cell corners, as SerialVofField sets them: u on the east face of
  // (i, j), v on the north face, ghost faces included, so that the discrete divergence telescopes.
  const int gw = Grid::ghost_width;
  auto x_face = [&](int i) { return grid.xf(i); };  // east face of cell i
  auto y_face = [&](int j) { return grid.yf(j); };
  {
    FieldArray u(grid.field_dm(), flow.face_velocity(0).local()), v(grid.field_dm(), flow.face_velocity(1).local());
    const CellBox& b = grid.owned();
    for (int j = b.ys - gw; j < b.ye() + gw; ++j)
      for (int i = b.xs - gw; i < b.xe() + gw; ++i) {
        u[j][i] = (psi(x_face(i), y_face(j)) - psi(x_face(i), y_face(j - 1))) / grid.dy(j);
        v[j][i] = -(psi(x_face(i), y_face(j)) - psi(x_face(i - 1), y_face(j))) / grid.dx(i);
      }
  }
  interface::SerialVofField serial(cells, cells, 1.0, 1.0);
  serial.set_velocity_from_stream_function(psi);
  const std::vector<double> start = gather_to_all(grid, soil.soil_fraction());
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) serial.c()(i, j) = start[size_t(j) * cells + i];
  serial.fill_ghosts();
  // A quarter turn in steps of sweep Courant number 0.4 at the disc's farthest point (one sweep pair each).
  const double dt = 0.4 * (1.0 / cells) / (omega * 0.45);
  const int steps = int(std::ceil(0.5 * M_PI / omega / dt));
  ASSERT_LE(serial.max_courant(dt), 0.45);
  for (int n = 0; n < steps; ++n) {
    soil.advect(flow, dt);
    serial.step(dt);
  }
  const std::vector<double> end = gather_to_all(grid, soil.soil_fraction());
  double largest = 0.0, moved = 0.0, volume = 0.0, serial_volume = 0.0;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const double c = end[size_t(j) * cells + i];
      largest = std::max(largest, std::abs(c - serial.c()(i, j)));
      moved = std::max(moved, std::abs(c - start[size_t(j) * cells + i]));
      volume += c;
      serial_volume += serial.c()(i, j);
    }
  std::printf("%d steps: largest difference from the serial driver %.3g (largest change %.3g); volumes %.15g, %.15g\n",
              steps, largest, moved, volume, serial_volume);
  EXPECT_GT(moved, 0.9);  // the disc has turned: cells went from full to empty
  EXPECT_LT(largest, 1e-12);
}

}  // namespace
}  // namespace granflow

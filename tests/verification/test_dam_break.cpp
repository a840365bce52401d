// Water column collapse against Martin & Moyce (1952), n^2 = 2: the shipped case
// cases/water_dam_break.toml (water and air, with the water's surface tension) run to T = t sqrt(2g/a) =
// 3.06, its history compared with the tabulated surge front Z(T) and residual column height H(tau)
// (validation/refdata/martin_moyce1952_n2_2_*.csv).
//
// Surge front: the points with 0.8 < T < 1.7 (Z_exp = 1.22 ... 1.89) are not held to 10 %. There the
// computed front runs ahead of the experiment by 0.16 - 0.24 in T (it reaches each Z about 9-13 ms
// early), 9 - 13 % in Z. This is not a resolution effect: on 294 x 126 cells (a/48) the deviations
// are the same within 1 % of Z, and they grow slightly as the time step goes to zero (courant 0.1 and
// dt <= 2e-4 s: 14.5 % at T = 1.19, 9.9 % at T = 1.63, 8.5 % at T = 1.83), so the model's instantaneous
// release of the column, not the discretisation, sets it. The surface tension takes 1.3 % off it
// (14.6 % at T = 1.19 without). Other Navier-Stokes/VoF comparisons with these data shift the simulated
// time by 0.175 in T to match the early points; that shift would make the residual column fall late by
// 0.044 of its height, beyond the table's reading accuracy, so it is not used here
// (docs/benchmark_dam_break.md).
// For those points the test checks that the front is ahead of the experiment and within 15 %.
// T = 1.63 is in that window too: the shipped settings give 8.6 % there, but the time-step-converged
// value, 9.9 %, is too near 10 % for a 10 % bound at that point to test more than the time-step error.
// Every other point with T <= 3, the first (T = 0.41, Z - 1 = 2.7 cells) included, must be within 10 %.
//
// Residual height: the table's H is read on a 1/4-inch grid, steps of 1/18 = 0.056 of the initial
// height, so the readings carry +-0.028; the computed H (height of water in the first column) must be
// within that at every point with T = sqrt(2) tau <= 3.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

constexpr double a = 0.05715;  // column width, 2.25 in
constexpr double g = 9.81;

TEST(DamBreak, MartinMoyceColumnCollapse) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto out = test::scratch("dam_break");
  // T = 3.06 at t = 0.165 s; no field files, only the history.
  const CaseConfig config = load_case(test::repo_path("cases/water_dam_break.toml"),
                                      {"output.progress_seconds=0", "time.end=0.165", "output.fields=false"});
  RunSummary s;
  {
    Simulation sim(PETSC_COMM_WORLD, config, out);
    s = sim.run();
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  auto hist = test::read_csv((out / "history.csv").string());
  MPI_Barrier(PETSC_COMM_WORLD);
  if (rank == 0) std::filesystem::remove_all(out);
  // Each rank reads the history and checks it; only rank 0 prints.
  auto say = [rank](const char* format, auto... args) {
    if (rank == 0) std::printf(format, args...);
  };
  ASSERT_GT(hist["time"].size(), 10u);
  ASSERT_NEAR(s.time, 0.165, 1e-9);

  // The column starts at Z = 1, H = 1 (t = 0 is not a history row).
  std::vector<double> T{0.0}, tau{0.0}, Z{1.0}, H{1.0};
  for (size_t k = 0; k < hist["time"].size(); ++k) {
    T.push_back(hist["time"][k] * std::sqrt(2 * g / a));
    tau.push_back(hist["time"][k] * std::sqrt(g / a));
    Z.push_back(hist["toe_contour"][k] / a);
    H.push_back(hist["wall_height"][k] / (2 * a));
  }

  // Dense-phase volume over the run (initial volume a * 2a: the column's edges lie on cell faces).
  const auto& vol = hist["soil_volume"];
  double drift = 0.0;
  for (double v : vol) test::keep_largest(drift, std::abs(v / vol.front() - 1.0));
  say("dam break: %ld steps, %.1f s wall, t = %.3f s (T = %.2f)\n", s.steps, s.wall_seconds, s.time, T.back());
  say("water volume %.12e m^2 (a * 2a = %.12e), largest relative drift %.2e, end %.2e\n", vol.front(),
              a * 2 * a, drift, s.soil_volume_error);
  EXPECT_LT(drift, 1e-10);
  EXPECT_LT(std::abs(s.soil_volume_error), 1e-10);
  EXPECT_NEAR(vol.front(), a * 2 * a, 1e-12 * a * a);

  auto front = test::read_csv(test::repo_path("validation/refdata/martin_moyce1952_n2_2_surge_front.csv"));
  say("     T  Z_exp  Z_sim  |dZ|/Z_exp  lead in T  bound\n");
  double worst_strict = 0.0, worst_early = 0.0;
  int compared = 0;
  for (size_t k = 0; k < front["T"].size(); ++k) {
    const double Te = front["T"][k], Ze = front["Z"][k];
    if (Te > 3.0) continue;
    ++compared;
    const double Zs = test::interp(T, Z, Te);
    const double dev = std::abs(Zs - Ze) / Ze;
    const double lead = Te - test::interp(Z, T, Ze);  // Z is increasing over this range
    const bool early = Te > 0.8 && Te < 1.7;
    say("  %4.2f  %5.2f  %5.3f  %9.4f  %9.3f  %s\n", Te, Ze, Zs, dev, lead, early ? "15 %, ahead" : "10 %");
    if (early) {
      test::keep_largest(worst_early, dev);
      EXPECT_LT(dev, 0.15) << "T = " << Te;
      EXPECT_GT(Zs, Ze) << "T = " << Te << ": the early front should run ahead of the experiment";
    } else {
      test::keep_largest(worst_strict, dev);
      EXPECT_LT(dev, 0.10) << "T = " << Te;
    }
  }
  EXPECT_EQ(compared, 13);
  say("surge front: largest |dZ|/Z_exp %.4f on the 9 points held to 10 %%, %.4f on the 4 early points\n",
              worst_strict, worst_early);

  auto resid = test::read_csv(test::repo_path("validation/refdata/martin_moyce1952_n2_2_residual_height.csv"));
  say("   tau  H_exp  H_sim  H_sim-H_exp\n");
  double worst_h = 0.0, worst_h_rel = 0.0;
  int heights_compared = 0;
  for (size_t k = 0; k < resid["tau"].size(); ++k) {
    const double te = resid["tau"][k], He = resid["H"][k];
    if (std::sqrt(2.0) * te > 3.0) continue;
    ++heights_compared;
    const double Hs = test::interp(tau, H, te);
    say("  %4.2f  %5.2f  %5.3f  %+9.4f\n", te, He, Hs, Hs - He);
    test::keep_largest(worst_h, std::abs(Hs - He));
    test::keep_largest(worst_h_rel, std::abs(Hs - He) / He);
    EXPECT_LT(std::abs(Hs - He), 0.5 / 18.0) << "tau = " << te;
  }
  say("residual height: largest |H_sim - H_exp| %.4f of the initial height (%.4f relative)\n", worst_h,
              worst_h_rel);
  EXPECT_EQ(heights_compared, 9);  // the table's points with T <= 3
}

// A water column has no friction to speak of: what it releases is kinetic energy and, through its
// small viscosity and the numerics, dissipated heat, never more. Every pressure coupling must keep
// that budget. PISO once averaged the faces' forces to the cell: the cell under the free surface
// took half the force of the face to the air with a density of its own, and here the column
// gained 35 % energy by t = 0.1 s, its kinetic energy 1.74 times what it had released, its front
// 0.162 m against 0.132 m. Half the case's resolution (a/12), to t = 0.1 s (T = 1.9), without the
// surface tension, whose energy in the interface the budget does not count.
TEST(DamBreak, EveryCouplingKeepsTheEnergyBudget) {
  double projection_front = 0.0;
  for (const char* coupling : {"projection", "piso", "coupled"}) {
    const auto out = test::scratch(std::string("dam_break_energy_") + coupling);
    {
      Simulation sim(PETSC_COMM_WORLD,
                     load_case(test::repo_path("cases/water_dam_break.toml"),
                               {"output.progress_seconds=0", "time.end=0.1", "output.fields=false",
                                "mesh.cells=[74,32]", "mesh.upper=[0.35242, 0.1524]", "soil.surface_tension=0",
                                std::string("numerics.pressure_coupling=") + coupling}),
                     out);
      sim.run();
    }
    MPI_Barrier(PETSC_COMM_WORLD);
    auto hist = test::read_csv((out / "history.csv").string());
    MPI_Barrier(PETSC_COMM_WORLD);
    if (!test::is_root()) continue;
    std::filesystem::remove_all(out);
    const size_t n = hist["time"].size();
    ASSERT_GT(n, 10u) << coupling;
    const double start = hist["potential_energy"][0] + hist["kinetic_energy"][0];
    double largest_gain = -1.0;
    for (size_t k = 0; k < n; ++k)
      test::keep_largest(largest_gain, (hist["potential_energy"][k] + hist["kinetic_energy"][k] +
                                             hist["dissipated_energy"][k]) / start - 1.0);
    const double released = hist["potential_energy"][0] - hist["potential_energy"][n - 1];
    const double kinetic_share = hist["kinetic_energy"][n - 1] / released;
    const double front = hist["toe_contour"][n - 1];
    if (projection_front == 0.0) projection_front = front;
    std::printf("%s: largest gain of potential + kinetic + dissipated energy %+.2e of the start; at t = 0.1 s "
                "kinetic energy %.3f of the released, front %.4f m\n",
                coupling, largest_gain, kinetic_share, front);
    EXPECT_LT(largest_gain, 1e-2) << coupling;  // measured 4.3e-3 (projection, coupled), 8.7e-4 (PISO)
    EXPECT_GT(kinetic_share, 0.8) << coupling;  // the water is not held back either
    EXPECT_NEAR(front, projection_front, 2 * a / 12) << coupling;
  }
}

// A column that fills the tank to its open top: as it falls, air enters through the top where water
// was. The coupled solve's face fluxes there must be those of its continuity rows, whose inflow
// pressure p0 - rho |v_P|^2 / 2 was taken before the solve changed v_P; taken anew after it, the
// water's volume grew by 2e-5 in 0.03 s.
TEST(DamBreak, ColumnFallingFromTheOpenTopKeepsItsVolume) {
  const auto out = test::scratch("dam_break_full_column");
  RunSummary s;
  {
    Simulation sim(PETSC_COMM_WORLD,
                   load_case(test::repo_path("cases/water_dam_break.toml"),
                             {"output.progress_seconds=0", "time.end=0.05", "output.fields=false", "mesh.cells=[74,32]",
                              "mesh.upper=[0.35242, 0.1524]", "numerics.pressure_coupling=coupled",
                              "initial.soil=[{shape = \"box\", lower = [0.0, 0.0], upper = [0.05715, 0.1524]}]"}),
                   out);
    s = sim.run();
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  auto hist = test::read_csv((out / "history.csv").string());
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!test::is_root()) return;
  std::filesystem::remove_all(out);
  const auto& vol = hist["soil_volume"];
  double drift = 0.0;
  for (double v : vol) test::keep_largest(drift, std::abs(v / vol.front() - 1.0));
  std::printf("full column under an open top, coupled: %ld steps, largest volume drift %.2e, outflow %.2e\n", s.steps,
              drift, hist["soil_outflow"].back());
  EXPECT_GT(s.steps, 10);
  EXPECT_LT(drift, 1e-12);
  EXPECT_EQ(hist["soil_outflow"].back(), 0.0);
}

}  // namespace
}  // namespace granflow

// A checkpoint holds the fields over the whole mesh, so a run may continue on another number of
// ranks: stopped on one rank and continued on two, or the other way round, it must end where the
// run that was never stopped ends, to the solver's tolerance, with the totals kept per rank (the
// soil carried out, the energy dissipated by Lode angle) carried over. Run under mpirun -np 2
// (tests/parallel.cmake).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "../verification/restart_check.hpp"

namespace granflow {
namespace {

using test::EndState;

// Stopped after this many steps (of 86), the run continues from its checkpoint at t = 0.2 s, when soil
// has been leaving through the east side since t = 0.16 s.
constexpr long stop_after = 70;

// The shipped collapse settings on a small mesh whose east side the soil reaches before the end, so
// that some soil leaves the domain. Each rank factorises the whole region itself (PCREDUNDANT), so
// that one and two ranks solve the same systems (docs/benchmarks.md: MUMPS's factorisation
// distributed over ranks sums in an order that depends on timing, which the collapse amplifies).
// Each rank factorises the whole region itself (with solver.coupled.pc_type = "redundant").
void factorise_on_every_rank() {
  PetscOptionsSetValue(nullptr, "-coupled_redundant_pc_type", "lu");
  PetscOptionsSetValue(nullptr, "-coupled_redundant_pc_factor_mat_solver_type", "mumps");
}

CaseConfig collapse() {
  factorise_on_every_rank();
  return test::bui2008_case_at_courant_one({"mesh.cells=[60,20]", "mesh.upper=[0.3,0.2]", "time.end=0.4",
                                            "output.interval=0.1", "output.progress_seconds=0", "numerics.air_band=5",
                                            "solver.coupled.pc_type=redundant"});
}

// What the comparison reads from a finished run, on the root of its communicator.
struct Finished {
  EndState end;
  std::map<std::string, std::vector<double>> history, lode;
};

Finished finish(Simulation& sim, const RunSummary& s, const std::filesystem::path& dir) {
  Finished f{test::end_state(sim, s.steps), {}, {}};
  int rank;
  MPI_Comm_rank(sim.grid().comm(), &rank);
  if (rank == 0) {
    f.history = test::read_csv((dir / "history.csv").string());
    f.lode = test::read_csv((dir / "lode_dissipation.csv").string());
  }
  return f;
}

Finished run_whole(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& dir) {
  Simulation sim(comm, config, dir);
  const RunSummary s = sim.run();
  return finish(sim, s, dir);
}

Finished restart(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& dir, double& checkpoint_time) {
  Simulation sim(comm, config, dir);
  sim.restart();
  checkpoint_time = sim.time();
  const RunSummary s = sim.run();
  return finish(sim, s, dir);
}

// On rank 0: the continued run against the one never stopped.
void expect_same_run(const Finished& resumed, const Finished& whole, const char* what) {
  EXPECT_EQ(resumed.end.time, whole.end.time);
  const char* names[] = {"u", "v", "p", "c"};
  // m/s, m/s, Pa, 1. Measured either way: 2-4e-15 m/s, 2e-12 Pa, 2e-15, the round-off of sums taken
  // in another order; the bounds are those of the rank-consistency tests.
  const double tolerance[] = {1e-9, 1e-9, 1e-4, 1e-9};
  ASSERT_EQ(resumed.end.fields.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    const double d = test::max_difference(resumed.end.fields[k], whole.end.fields[k]);
    std::printf("%s: largest difference in %s %.2e\n", what, names[k], d);
    EXPECT_LT(d, tolerance[k]) << names[k];
  }
  // The totals each rank keeps a share of: the soil carried out through the east side and the energy
  // dissipated by Lode angle.
  const auto& out_resumed = resumed.history.at("soil_outflow");
  const auto& out_whole = whole.history.at("soil_outflow");
  ASSERT_EQ(out_resumed.size(), out_whole.size());
  // Soil had begun to leave before the checkpoint (t = 0.2 s), so each rank's share of it was handed over.
  const auto& time = whole.history.at("time");
  const size_t at_checkpoint = size_t(std::upper_bound(time.begin(), time.end(), 0.2 + 1e-9) - time.begin()) - 1;
  EXPECT_GT(out_whole[at_checkpoint], 1e-6 * whole.history.at("soil_volume").front());
  EXPECT_NEAR(out_resumed.back(), out_whole.back(), 1e-9 * out_whole.back());
  const auto& lode_resumed = resumed.lode.at("energy");
  const auto& lode_whole = whole.lode.at("energy");
  ASSERT_EQ(lode_resumed.size(), lode_whole.size());
  double total = 0.0;
  for (double e : lode_whole) total += e;
  EXPECT_GT(total, 0.0);
  EXPECT_LT(test::max_difference(lode_resumed, lode_whole), 1e-9 * total);
}

// The case run whole on rank 0, and into another directory stopped there after `stop_after` steps
// and continued from its checkpoint on every rank (scratch directories named after `name`).
struct OneThenTwo {
  Finished whole, resumed;  // on rank 0
  double checkpoint_time = 0.0;
};
OneThenTwo one_rank_then_two(const CaseConfig& config, const std::string& name, long steps) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto whole_dir = test::scratch(name + "_whole"), split_dir = test::scratch(name + "_split");
  test::remove_scratch(whole_dir);
  test::remove_scratch(split_dir);
  OneThenTwo r;
  if (rank == 0) {
    r.whole = run_whole(PETSC_COMM_SELF, config, whole_dir);
    test::run_and_kill(PETSC_COMM_SELF, config, split_dir, steps);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  r.resumed = restart(PETSC_COMM_WORLD, config, split_dir, r.checkpoint_time);
  test::remove_scratch(whole_dir);
  test::remove_scratch(split_dir);
  return r;
}

TEST(RestartOtherRanks, CollapseStoppedOnOneRankContinuesOnTwo) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const OneThenTwo r = one_rank_then_two(collapse(), "one_to_two", stop_after);
  if (rank == 0) {
    EXPECT_GE(r.checkpoint_time, 0.2 - 1e-12);
    expect_same_run(r.resumed, r.whole, "one rank, then two");
  }
}

TEST(RestartOtherRanks, CollapseStoppedOnTwoRanksContinuesOnOne) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto whole_dir = test::scratch("two_to_one_whole"), split_dir = test::scratch("two_to_one_split");
  test::remove_scratch(whole_dir);
  test::remove_scratch(split_dir);
  const CaseConfig config = collapse();
  test::run_and_kill(PETSC_COMM_WORLD, config, split_dir, stop_after);
  if (rank == 0) {
    const Finished whole = run_whole(PETSC_COMM_SELF, config, whole_dir);
    double checkpoint_time = 0.0;
    const Finished resumed = restart(PETSC_COMM_SELF, config, split_dir, checkpoint_time);
    EXPECT_GE(checkpoint_time, 0.2 - 1e-12);
    expect_same_run(resumed, whole, "two ranks, then one");
  }
  test::remove_scratch(whole_dir);
  test::remove_scratch(split_dir);
}

// A mesh of layers: the quarter column of cases/lube2004_a05_3d.toml on cells of 2 cm (20 x 8 x 20)
// under its coupled solve, stopped on one rank after its checkpoint at t = 0.05 s and continued on
// two, against the run never stopped on one rank; each rank factorises the whole region itself, as
// above. The 3D checkpoint's planes of layers, read into another decomposition. Each outer iteration
// by its own factorisation: under the case's "first_factorisation" a later iteration takes a fixed
// number of Krylov iterations on the first's factorisation, whose unconverged remainder depends on
// that factorisation's pivots (other with the rows of two ranks, and with where the last checkpoint
// had the factorisations made anew): the last step came out 1e-4 m/s apart, in runs never stopped
// too (one rank against two, or checkpoints at other times), while every field at the outputs between
// agreed to 1e-15. Measured with own factorisations: the same to the bit.
TEST(RestartOtherRanks, AColumnOnAMeshOfLayersStoppedOnOneRankContinuesOnTwo) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  factorise_on_every_rank();
  const CaseConfig config =
      load_case(test::repo_path("cases/lube2004_a05_3d.toml"),
                {"mesh.cells=[20,8,20]", "time.end=0.1", "output.times=[0.05]", "output.progress_seconds=0",
                 "output.fields=false", "solver.coupled.pc_type=redundant",
                 "numerics.later_iterations=\"own_factorisation\""});
  const auto [whole, resumed, checkpoint_time] = one_rank_then_two(config, "layers_one_to_two", 16);  // of 19 steps
  if (rank == 0) {
    EXPECT_GE(checkpoint_time, 0.05 - 1e-12);
    EXPECT_EQ(resumed.end.time, whole.end.time);
    const char* names[] = {"u", "v", "w", "p", "c"};
    const double tolerance[] = {1e-9, 1e-9, 1e-9, 1e-4, 1e-9};  // m/s, Pa, 1: as the collapse's above
    ASSERT_EQ(resumed.end.fields.size(), 5u);
    for (size_t k = 0; k < 5; ++k) {
      const double d = test::max_difference(resumed.end.fields[k], whole.end.fields[k]);
      std::printf("3D column, one rank, then two: largest difference in %s %.2e\n", names[k], d);
      EXPECT_LT(d, tolerance[k]) << names[k];
    }
    EXPECT_GT(test::max_difference(whole.end.fields[0], std::vector<double>(whole.end.fields[0].size(), 0.0)), 0.1);
    const auto& kinetic = whole.history.at("kinetic_energy");
    EXPECT_NEAR(resumed.history.at("kinetic_energy").back(), kinetic.back(), 1e-9 * kinetic.back());
  }
}

}  // namespace
}  // namespace granflow

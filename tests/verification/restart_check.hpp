#pragma once
// Checkpoint and restart, shared by the one-rank and the two-rank tests: a run stopped
// between outputs and restarted from its last checkpoint must end exactly where the run that was
// never stopped ends, field by field and row by row of the history.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "mesh/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow::test {

struct EndState {
  double time = 0.0;
  long steps = 0;
  std::vector<std::vector<double>> fields;  // u, v (w), p (and c, and the soil materials' shares)
};

inline EndState end_state(Simulation& sim, long steps) {
  EndState e{sim.time(), steps, {}};
  for (int a = 0; a < sim.grid().dimension(); ++a) e.fields.push_back(gather_to_root(sim.grid(), sim.flow().velocity(a)));
  e.fields.push_back(gather_to_root(sim.grid(), sim.flow().pressure()));
  if (sim.soil()) e.fields.push_back(gather_to_root(sim.grid(), sim.soil()->soil_fraction()));
  if (sim.soil())
    for (int k = 1; k <= sim.soil()->material_count(); ++k)
      e.fields.push_back(gather_to_root(sim.grid(), sim.soil()->material_share(k)));
  return e;
}

// Runs the case on `comm` into `dir` and stops it as if killed after `stop_after` steps, between
// outputs: nothing more is written.
inline void run_and_kill(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& dir, long stop_after) {
  struct Killed {};
  Simulation sim(comm, config, dir);
  try {
    sim.run([&, steps = 0L](const Simulation&, double) mutable {
      if (++steps == stop_after) throw Killed{};
    });
    ADD_FAILURE() << "the run ended before step " << stop_after;
  } catch (const Killed&) {
  }
  EXPECT_LT(sim.time(), config.time.end);
}

// On all ranks of PETSC_COMM_WORLD: runs the case whole into one directory; into another, kills it
// after `stop_after` steps and runs it again from the checkpoint, which `before_restart` (if given)
// may change first, on the first rank. Returns the checkpoint's time.
inline double expect_restart_reproduces(const std::string& case_file, std::vector<std::string> overrides,
                                        long stop_after, bool has_history,
                                        const std::function<void(const std::filesystem::path&)>& before_restart = {}) {
  const auto whole_dir = scratch("restart_whole"), split_dir = scratch("restart_split");
  remove_scratch(whole_dir);
  remove_scratch(split_dir);
  const CaseConfig config = load_case(repo_path(case_file), overrides);
  EndState whole;
  {
    Simulation sim(PETSC_COMM_WORLD, config, whole_dir);
    const RunSummary s = sim.run();
    whole = end_state(sim, s.steps);
  }
  run_and_kill(PETSC_COMM_WORLD, config, split_dir, stop_after);
  if (before_restart) {
    if (is_root()) before_restart(split_dir / "checkpoint");
    MPI_Barrier(PETSC_COMM_WORLD);
  }
  double checkpoint_time = 0.0;
  EndState resumed;
  {
    Simulation sim(PETSC_COMM_WORLD, config, split_dir);
    sim.restart();
    checkpoint_time = sim.time();
    const RunSummary s = sim.run();
    resumed = end_state(sim, s.steps);
  }
  EXPECT_GT(checkpoint_time, 0.0);
  EXPECT_EQ(resumed.time, whole.time);
  EXPECT_LT(resumed.steps, whole.steps);
  for (size_t k = 0; k < whole.fields.size(); ++k) {
    EXPECT_EQ(resumed.fields[k].size(), whole.fields[k].size());
    if (resumed.fields[k].size() != whole.fields[k].size()) continue;
    size_t differ = 0;
    for (size_t n = 0; n < whole.fields[k].size(); ++n) differ += resumed.fields[k][n] != whole.fields[k][n];
    EXPECT_EQ(differ, 0u) << "field " << k << " differs in " << differ << " cells";
  }
  if (has_history) EXPECT_EQ(file_text(split_dir / "history.csv"), file_text(whole_dir / "history.csv"));
  // The series of field files, where the case writes fields (a missing file reads as empty text).
  const bool fields = std::filesystem::exists(whole_dir / "fields.pvd");
  EXPECT_EQ(std::filesystem::exists(split_dir / "fields.pvd"), fields);
  if (fields) EXPECT_EQ(file_text(split_dir / "fields.pvd"), file_text(whole_dir / "fields.pvd"));
  remove_scratch(whole_dir);
  remove_scratch(split_dir);
  return checkpoint_time;
}

}  // namespace granflow::test

// Checkpoint and restart (SPEC 6): a run stopped between outputs and restarted from its last
// checkpoint ends exactly where the run that was never stopped ends, field by field and row by row
// of the history, on one rank. The collapse takes the shipped numerics (coupled solve, look-ahead
// viscosity from the last two steps, two VoF sweeps), so every piece of state a step starts from
// must come back; the cavity has no soil phase.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/gather.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / (name + "_" + std::to_string(getpid()));
}

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct EndState {
  double time = 0.0;
  long steps = 0;
  std::vector<std::vector<double>> fields;  // u, v, p (and c)
};

EndState end_state(Simulation& sim, long steps) {
  EndState e{sim.time(), steps, {}};
  for (int a = 0; a < 2; ++a) e.fields.push_back(gather_to_root(sim.grid(), sim.flow().velocity(a)));
  e.fields.push_back(gather_to_root(sim.grid(), sim.flow().pressure()));
  if (sim.soil()) e.fields.push_back(gather_to_root(sim.grid(), sim.soil()->soil_fraction()));
  return e;
}

// Runs the case whole into one directory; into another, stops it after `stop_after` steps and runs
// it again from the checkpoint. Returns the checkpoint's time.
double expect_restart_reproduces(const std::string& case_file, std::vector<std::string> overrides, long stop_after,
                                 bool has_history) {
  const auto whole_dir = scratch("granflow_restart_whole"), split_dir = scratch("granflow_restart_split");
  std::filesystem::remove_all(whole_dir);
  std::filesystem::remove_all(split_dir);
  const CaseConfig config = load_case(test::repo_path(case_file), overrides);
  EndState whole;
  {
    Simulation sim(PETSC_COMM_WORLD, config, whole_dir);
    const RunSummary s = sim.run();
    whole = end_state(sim, s.steps);
  }
  overrides.push_back("time.max_steps=" + std::to_string(stop_after));
  {
    Simulation stopped(PETSC_COMM_WORLD, load_case(test::repo_path(case_file), overrides), split_dir);
    stopped.run();
    EXPECT_LT(stopped.time(), config.time.end);
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
  EXPECT_EQ(file_text(split_dir / "fields.pvd"), file_text(whole_dir / "fields.pvd"));
  std::filesystem::remove_all(whole_dir);
  std::filesystem::remove_all(split_dir);
  return checkpoint_time;
}

TEST(Restart, CollapseContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/bui2008_experiment.toml",
      {"mesh.cells=[60,20]", "time.end=0.3", "output.interval=0.1", "output.progress_seconds=0"}, 45, true);
  std::printf("collapse restarted from its checkpoint at t = %.3g s\n", t);
}

TEST(Restart, CavityContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/lid_driven_cavity_re100.toml",
      {"mesh.cells=[24,24]", "time.end=1.0", "time.max_dt=0.02", "time.steady_tolerance=0", "output.interval=0.25",
       "output.progress_seconds=0"},
      30, false);
  std::printf("cavity restarted from its checkpoint at t = %.3g s\n", t);
}

TEST(Restart, RefusesAMissingOrForeignCheckpoint) {
  const auto dir = scratch("granflow_restart_foreign");
  std::filesystem::remove_all(dir);
  const std::vector<std::string> small{"mesh.cells=[30,10]", "time.end=0.05", "output.interval=0.05",
                                       "output.progress_seconds=0", "output.fields=false"};
  {
    Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path("cases/bui2008_experiment.toml"), small), dir);
    EXPECT_THROW(sim.restart(), CheckpointError);  // nothing written yet
    sim.run();
  }
  auto other = small;
  other[0] = "mesh.cells=[32,10]";
  Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path("cases/bui2008_experiment.toml"), other), dir);
  try {
    sim.restart();
    ADD_FAILURE() << "a checkpoint of another mesh was taken";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("30 x 10"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace granflow

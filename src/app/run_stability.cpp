#include "app/run_stability.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/run_case.hpp"
#include "io/atomic_file.hpp"
#include "io/case_advice.hpp"
#include "io/case_error.hpp"
#include "io/collective_failure.hpp"
#include "io/run_directory.hpp"
#include "io/run_lock.hpp"
#include "solver/simulation.hpp"

namespace granflow {

namespace {

constexpr const char* table_name = "stability.csv";

// The earlier analysis in dir: its table and its trials' directories (F_<factor> holding any of a
// run's files, io/run_directory.hpp).
std::vector<std::filesystem::path> earlier_analysis(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == table_name || (name.starts_with("F_") && !run_files_in(entry.path(), {}).empty()))
      found.push_back(entry.path());
  }
  return found;
}

// The trials so far, rewritten whole after each one, so that an analysis stopped or killed keeps the
// table of the trials it finished.
void write_table(const std::filesystem::path& path, const std::vector<StrengthTrial>& trials) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "factor,fails,diverged,largest_displacement_m,time_s,steps,unconverged_steps,wall_seconds,directory\n";
    for (const auto& t : trials)
      out << fmt::format("{},{},{},{:.6g},{:.6g},{},{},{:.3f},{}\n", t.factor, int(t.fails), int(t.diverged),
                         t.largest_displacement, t.time, t.steps, t.unconverged_steps, t.wall_seconds,
                         trial_directory(".", t.factor).filename().string());
  });
}

}  // namespace

int run_stability(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
                  bool overwrite, const StrengthReductionSettings& settings) {
  const CaseConfig config = load_case(case_file, overrides);
  check_solver_options(config);
  // A case with nothing to reduce, and the first trial's simulation, made and dropped before the
  // directory is touched: it checks what the case file alone cannot, and PETSc, which refuses an
  // option it does not know by ending the process, reads the solvers' options there (as a run's does).
  Simulation(PETSC_COMM_WORLD, reduced_strength(config, settings.first_factor), "");
  if (out_dir.empty()) out_dir = default_output_directory(case_file, "_stability").string();
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // One analysis (or run) at a time in the directory, held by rank 0 for the whole analysis
  // (io/run_lock.hpp). An earlier analysis replaced with --overwrite is set aside until the first trial
  // has ended, and put back if the analysis fails before (io/run_directory.hpp).
  RunLock lock;
  std::string problem;
  bool set_aside = false;
  if (rank == 0) {
    std::error_code ec;
    if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
      problem = fmt::format("-o {}: not a directory", out_dir);
    else if (problem = inside_a_runs_own_directory(out_dir); !problem.empty()) {
    }
    else if (std::filesystem::create_directories(out_dir, ec); ec)
      problem = fmt::format("-o {}: cannot make the directory: {}", out_dir, ec.message());
    else if (problem = lock.take(out_dir); !problem.empty()) {
    } else if (const auto aside = set_aside_run_in(out_dir); !aside.empty())
      problem = fmt::format("{} holds {}, the files of an earlier analysis that an analysis with --overwrite set "
                            "aside and was stopped before its first trial ended: move them back into {} (or remove "
                            "{}), then run again",
                            out_dir, aside.string(), out_dir, aside.string());
    else if (const auto earlier = earlier_analysis(out_dir); !earlier.empty()) {
      if (!overwrite)
        problem = fmt::format("{} holds an earlier analysis ({}): replace it with --overwrite, or choose another "
                              "directory with -o",
                              out_dir, earlier.front().string());
      else if (problem = set_aside_run(out_dir, earlier); problem.empty())
        set_aside = true;
    }
  }
  if (auto text = first_failure(PETSC_COMM_WORLD, problem); !text.empty()) throw CaseError(text);
  std::vector<std::string> advice;  // warnings on the case's choices, which a failure may come from
  if (rank == 0) {
    fmt::print("granflow: factor of safety of {} by strength reduction (C / F, tan(phi) / F), each trial to t = {} s, "
               "output in {}\n",
               config.title, config.time.end, out_dir);
    std::fflush(stdout);
    advice = case_advice(config);
    for (const auto& line : advice) fmt::print(stderr, "warning: {}\n", line);
  }
  auto under_way = [&] {
    if (set_aside) discard_set_aside_run(out_dir);
    set_aside = false;
  };
  StrengthReductionResult r;
  std::vector<StrengthTrial> finished;
  try {
    r = factor_of_safety(PETSC_COMM_WORLD, config, out_dir, settings, [&](const StrengthTrial& t) {
        if (rank != 0) return;
        under_way();
        finished.push_back(t);
        write_table(std::filesystem::path(out_dir) / table_name, finished);
        fmt::print("F = {}: {} (largest displacement {:.3g} m at t = {:.4g} s; {} steps{}, {:.1f} s)\n", t.factor,
                   t.diverged ? "fails (diverged)" : t.fails ? "fails" : "stands", t.largest_displacement, t.time,
                   t.steps,
                   t.unconverged_steps > 0 ? fmt::format(", {} of them unconverged", t.unconverged_steps) : std::string(),
                   t.wall_seconds);
        std::fflush(stdout);
      });
  } catch (...) {
    if (set_aside) {  // the new analysis's trials go, and the earlier one comes back
      std::error_code ec;
      for (const auto& p : earlier_analysis(out_dir)) std::filesystem::remove_all(p, ec);
      restore_set_aside_run(out_dir, {});
    }
    throw;
  }
  under_way();  // a search of no trial
  if (rank == 0) write_table(std::filesystem::path(out_dir) / table_name, r.trials);
  if (!r.bracketed()) {
    // Trials that all diverged say nothing of the soil's strength: the solution broke down at every
    // factor, down to the strongest soil tried, and the first trial's message says where.
    const bool all_diverged = !r.trials.empty() && std::all_of(r.trials.begin(), r.trials.end(),
                                                               [](const StrengthTrial& t) { return t.diverged; });
    if (all_diverged) {
      if (rank == 0)
        fmt::print(stderr, "error: every trial diverged, down to F = {}: no factor of safety found, as the solution "
                           "broke down before the soil's strength could decide (the first trial, F = {}: {})\n",
                   r.fails_at, r.trials.front().factor, r.trials.front().divergence);
      return 3;
    }
    if (rank == 0) {
      if (r.stands_at > 0.0)
        fmt::print(stderr, "error: the soil stands at every factor tried, up to F = {} (the search goes no higher "
                           "than {}): no factor of safety found; a longer time.end gives weakened soil the time to move\n",
                   r.stands_at, settings.largest_factor);
      else
        fmt::print(stderr, "error: the soil fails at every factor tried, down to F = {} (the search goes no lower "
                           "than {}): no factor of safety found; it does not stand even with its strength multiplied{}\n",
                   r.fails_at, settings.smallest_factor,
                   advice.empty() ? "" : " (mind the warnings on the case's numerics above: they may be why)");
    }
    return 1;
  }
  if (rank == 0) {
    fmt::print("factor of safety: {:.3f} (stands at F = {}, fails at F = {}; trials in {})\n",
               0.5 * (r.stands_at + r.fails_at), r.stands_at, r.fails_at, out_dir);
    // The two trials that make the bracket decide the factor: a viscosity that lags behind the flow
    // there holds a soil at its limit a little longer.
    for (const auto& t : r.trials)
      if ((t.factor == r.stands_at || t.factor == r.fails_at) && t.unconverged_steps > 0) {
        fmt::print("note: the bracket's trials took steps whose outer iterations stopped at numerics.outer_iterations = "
                   "{} before numerics.outer_tolerance; near its limit a soil converges slowly, and more iterations "
                   "can lower the factor a little (docs/validation.md, \"An infinite slope\")\n",
                   config.flow.numerics.outer_iterations < 10 ? 10 : config.flow.numerics.outer_iterations);
        break;
      }
  }
  return 0;
}

}  // namespace granflow

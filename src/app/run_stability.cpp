#include "app/run_stability.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <cstdio>
#include <filesystem>

#include "app/run_case.hpp"
#include "io/atomic_file.hpp"
#include "io/case_error.hpp"
#include "io/collective_failure.hpp"
#include "io/run_directory.hpp"

namespace granflow {

namespace {

constexpr const char* table_name = "stability.csv";

// The earlier analysis in dir: its table and its trials' directories (F_<factor> holding a case record).
std::vector<std::filesystem::path> earlier_analysis(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == table_name || (name.starts_with("F_") && fs::exists(entry.path() / case_record_name, ec)))
      found.push_back(entry.path());
  }
  return found;
}

void write_table(const std::filesystem::path& path, const StrengthReductionResult& r) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "factor,fails,diverged,largest_displacement_m,time_s,steps,unconverged_steps,wall_seconds,directory\n";
    for (const auto& t : r.trials)
      out << fmt::format("{},{},{},{:.6g},{:.6g},{},{},{:.3f},{}\n", t.factor, int(t.fails), int(t.diverged),
                         t.largest_displacement, t.time, t.steps, t.unconverged_steps, t.wall_seconds,
                         trial_directory(".", t.factor).filename().string());
  });
}

}  // namespace

int run_stability(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
                  bool overwrite, const StrengthReductionSettings& settings) {
  const CaseConfig config = load_case(case_file, overrides);
  check_solver_methods(config);
  reduced_strength(config, settings.first_factor);  // a case with nothing to reduce, before any directory is made
  if (out_dir.empty())
    out_dir = (std::filesystem::path("out") / (std::filesystem::path(case_file).stem().string() + "_stability")).string();
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  std::string problem;
  if (rank == 0) {
    std::error_code ec;
    if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
      problem = fmt::format("-o {}: not a directory", out_dir);
    else if (const auto earlier = earlier_analysis(out_dir); !earlier.empty()) {
      if (!overwrite)
        problem = fmt::format("{} holds an earlier analysis ({}): replace it with --overwrite, or choose another "
                              "directory with -o",
                              out_dir, earlier.front().string());
      else
        for (const auto& p : earlier) std::filesystem::remove_all(p, ec);
    }
  }
  if (auto text = first_failure(PETSC_COMM_WORLD, problem); !text.empty()) throw CaseError(text);
  if (rank == 0) {
    fmt::print("granflow: factor of safety of {} by strength reduction (C / F, tan(phi) / F), each trial to t = {} s, "
               "output in {}\n",
               config.title, config.time.end, out_dir);
    std::fflush(stdout);
  }
  const StrengthReductionResult r = factor_of_safety(
      PETSC_COMM_WORLD, config, out_dir, settings, [&](const StrengthTrial& t) {
        if (rank != 0) return;
        fmt::print("F = {}: {} (largest displacement {:.3g} m at t = {:.4g} s; {} steps{}, {:.1f} s)\n", t.factor,
                   t.diverged ? "fails (diverged)" : t.fails ? "fails" : "stands", t.largest_displacement, t.time,
                   t.steps,
                   t.unconverged_steps > 0 ? fmt::format(", {} of them unconverged", t.unconverged_steps) : std::string(),
                   t.wall_seconds);
        std::fflush(stdout);
      });
  if (rank == 0) write_table(std::filesystem::path(out_dir) / table_name, r);
  if (!r.bracketed()) {
    if (rank == 0) {
      if (r.stands_at > 0.0)
        fmt::print(stderr, "error: the soil stands at every factor tried, up to F = {} (the search stops below {}): no "
                           "factor of safety found; a longer time.end gives weakened soil the time to move\n",
                   r.stands_at, settings.largest_factor);
      else
        fmt::print(stderr, "error: the soil fails at every factor tried, down to F = {} (the search stops above {}): "
                           "no factor of safety found; it does not stand even with its strength multiplied\n",
                   r.fails_at, settings.smallest_factor);
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

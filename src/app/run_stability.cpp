#include "app/run_stability.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/run_case.hpp"
#include "io/atomic_file.hpp"
#include "io/text_file.hpp"
#include "io/case_advice.hpp"
#include "io/case_error.hpp"
#include "io/collective_failure.hpp"
#include "io/run_directory.hpp"
#include "io/run_lock.hpp"
#include "solver/simulation.hpp"

namespace granflow {

namespace {

constexpr const char* table_name = stability_table_name;
constexpr std::size_t table_limit = std::size_t(64) << 20;    // bytes: some 500 000 trials
constexpr std::size_t record_limit = std::size_t(256) << 20;  // as a case file may be (polygons of many vertices)
constexpr const char* table_header =
    "factor,fails,diverged,largest_displacement_m,displacement_limit_m,time_s,steps,unconverged_steps,wall_seconds,"
    "directory";

// The trials so far, rewritten whole after each one, so that an analysis stopped or killed keeps the
// table of the trials it finished.
void write_table(const std::filesystem::path& path, const std::vector<StrengthTrial>& trials) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << table_header << "\n";
    for (const auto& t : trials)
      out << fmt::format("{},{},{},{:.6g},{},{:.6g},{},{},{:.3f},{}\n", t.factor, int(t.fails), int(t.diverged),
                         t.largest_displacement, t.displacement_limit, t.time, t.steps, t.unconverged_steps,
                         t.wall_seconds, trial_directory(".", t.factor).filename().string());
  });
}

// A line of a text file without the carriage return of a CRLF line end.
bool read_line(std::istream& in, std::string& line) {
  if (!std::getline(in, line)) return false;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

// The trials of the earlier analysis in `out`, from its table; a problem in `problem` (no analysis
// there, a table of another form, or a row that does not read). An analysis stopped in its first trial
// has trial directories and no table yet: none of its trials finished.
std::vector<StrengthTrial> read_table(const std::filesystem::path& out, std::string& problem) {
  namespace fs = std::filesystem;
  const fs::path path = out / table_name;
  std::vector<StrengthTrial> trials;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (analysis_files_in(out).empty())
      problem = fmt::format("no analysis to continue in {}: neither {} nor a trial's directory (F_<factor>) is there",
                            out.string(), table_name);
    return trials;
  }
  const TextFile file = read_text_file(path, table_limit);
  if (file.status != TextFile::Status::read) {
    problem = fmt::format("{}: cannot be read ({})", path.string(),
                          file.status == TextFile::Status::too_long ? "longer than any analysis's table" : file.reason);
    return trials;
  }
  std::istringstream in(file.text);
  std::string line;
  if (!read_line(in, line)) {
    problem = fmt::format("{}: empty, not the table of an analysis; start anew with --overwrite", path.string());
    return trials;
  }
  if (line != table_header) {
    problem = fmt::format("{}: not the table of an analysis this granflow can continue (its first line is not \"{}\"); "
                          "start anew with --overwrite",
                          path.string(), table_header);
    return trials;
  }
  for (int row = 2; read_line(in, line); ++row) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream text(line);
    for (std::string cell; std::getline(text, cell, ',');) cells.push_back(cell);
    StrengthTrial t;
    try {
      if (cells.size() != 10 || (cells[1] != "0" && cells[1] != "1") || (cells[2] != "0" && cells[2] != "1"))
        throw std::invalid_argument("row");
      size_t used = 0;
      auto number = [&used](const std::string& s) {
        const double x = std::stod(s, &used);
        if (used != s.size() || !std::isfinite(x)) throw std::invalid_argument(s);
        return x;
      };
      t.factor = number(cells[0]);
      t.fails = cells[1] == "1";
      t.diverged = cells[2] == "1";
      t.largest_displacement = number(cells[3]);
      t.displacement_limit = number(cells[4]);
      t.time = number(cells[5]);
      t.steps = long(number(cells[6]));
      t.unconverged_steps = long(number(cells[7]));
      t.wall_seconds = number(cells[8]);
      if (!(t.factor > 0.0) || cells[9] != trial_directory(".", t.factor).filename().string())
        throw std::invalid_argument("row");
    } catch (const std::exception&) {
      problem = fmt::format("{}: row {} is not a trial's (\"{}\"): the table is damaged; start anew with --overwrite",
                            path.string(), row, line);
      return {};
    }
    trials.push_back(t);
  }
  return trials;
}

// The case a trial's directory records, without the comment lines that say how it was run; empty if
// it cannot be read.
std::string recorded_case(const std::filesystem::path& trial) {
  const TextFile file = read_text_file(trial / case_record_name, record_limit);
  if (file.status != TextFile::Status::read) return {};
  std::istringstream in(file.text);
  std::string line, text;
  bool header = true;
  while (std::getline(in, line)) {
    if (header && (line.starts_with("#") || line.empty())) continue;
    header = false;
    text += line + "\n";
  }
  return text;
}

// Why the earlier analysis in out cannot be continued by this one (empty if it can): each trial of its
// table must be of this case at its factor, as its directory's record says, and judged by the same
// displacement limit. A listed trial whose directory or record is gone is dropped from `earlier`, and
// directories of trials not listed (not finished) are removed: they run again if the search reaches them.
// What was dropped or removed is said in `notes`.
std::string continue_earlier(const std::filesystem::path& out, const CaseConfig& config, double limit,
                             std::vector<StrengthTrial>& earlier, std::vector<std::string>& notes) {
  namespace fs = std::filesystem;
  std::vector<StrengthTrial> kept;
  for (const auto& t : earlier) {
    const fs::path dir = trial_directory(out, t.factor);
    if (std::abs(t.displacement_limit - limit) > 1e-12 * limit)
      return fmt::format("the analysis in {} judged its trials by a displacement of {} m, this one by {} m: continue it "
                         "with the same --displacement, or start anew with --overwrite",
                         out.string(), t.displacement_limit, limit);
    const std::string recorded = recorded_case(dir);
    if (recorded.empty()) {
      notes.push_back(fmt::format("{}: the trial at F = {} that {} lists has no {} there; it runs again if the search "
                                  "reaches it", dir.string(), t.factor, table_name, case_record_name));
      continue;
    }
    if (recorded != reduced_strength(config, t.factor).as_run + "\n")
      return fmt::format("the analysis in {} is of another case than this one (its trial at F = {} ran the case in {} "
                         "with other keys or values): continue it with the same case and --set, or start anew with "
                         "--overwrite",
                         out.string(), t.factor, (dir / case_record_name).string());
    kept.push_back(t);
  }
  earlier = std::move(kept);
  std::error_code ec;
  for (const auto& path : analysis_files_in(out)) {  // the table and the trials' directories
    const bool listed = path.filename() == table_name ||
                        std::any_of(earlier.begin(), earlier.end(), [&](const StrengthTrial& t) {
                          return trial_directory(".", t.factor).filename() == path.filename();
                        });
    if (listed) continue;
    notes.push_back(fmt::format("{}: a trial the earlier analysis did not finish; it runs again if the search "
                                "reaches it", path.string()));
    fs::remove_all(path, ec);
  }
  return {};
}

// The earlier trials, rank 0's, on every rank: the search must be the same on all.
std::vector<StrengthTrial> shared_trials(MPI_Comm comm, const std::vector<StrengthTrial>& mine) {
  constexpr int fields = 9;
  long count = long(mine.size());
  MPI_Bcast(&count, 1, MPI_LONG, 0, comm);
  std::vector<double> flat(size_t(count) * fields);
  for (size_t k = 0; k < mine.size(); ++k) {
    const auto& t = mine[k];
    const double row[fields] = {t.factor, double(t.fails), double(t.diverged), t.largest_displacement,
                                t.displacement_limit, t.time, double(t.steps), double(t.unconverged_steps), t.wall_seconds};
    std::copy(row, row + fields, flat.begin() + long(k) * fields);
  }
  MPI_Bcast(flat.data(), int(flat.size()), MPI_DOUBLE, 0, comm);
  std::vector<StrengthTrial> trials(static_cast<size_t>(count));
  for (size_t k = 0; k < trials.size(); ++k) {
    const double* row = flat.data() + k * fields;
    auto& t = trials[k];
    t.factor = row[0];
    t.fails = row[1] != 0.0;
    t.diverged = row[2] != 0.0;
    t.largest_displacement = row[3];
    t.displacement_limit = row[4];
    t.time = row[5];
    t.steps = long(row[6]);
    t.unconverged_steps = long(row[7]);
    t.wall_seconds = row[8];
    if (t.diverged)
      t.divergence = fmt::format("diverged in the earlier analysis ({})", trial_directory(".", t.factor).filename().string());
  }
  return trials;
}

}  // namespace

int run_stability(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
                  bool overwrite, bool restart, const StrengthReductionSettings& settings) {
  const CaseConfig config = load_case(case_file, overrides);
  check_solver_options(config);
  // A case with nothing to reduce, and the first trial's simulation, made and dropped before the
  // directory is touched: it checks what the case file alone cannot, and PETSc, which refuses an
  // option it does not know by ending the process, reads the solvers' options there (as a run's does).
  // The displacement limit comes from its mesh.
  const double limit = [&] {
    Simulation first(PETSC_COMM_WORLD, reduced_strength(config, settings.first_factor), "");
    return settings.displacement_limit > 0.0 ? settings.displacement_limit : first.soil()->moved_distance();
  }();
  if (out_dir.empty()) out_dir = default_output_directory(case_file, "_stability").string();
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // One analysis (or run) at a time in the directory, held by rank 0 for the whole analysis
  // (io/run_lock.hpp). An earlier analysis replaced with --overwrite is set aside until the first trial
  // has ended, and put back if the analysis fails before (io/run_directory.hpp).
  RunLock lock;
  std::string problem;
  bool set_aside = false;
  std::vector<StrengthTrial> earlier;  // an earlier analysis's trials, continued (restart)
  std::vector<std::string> notes;      // and what of it runs again
  if (rank == 0) {
    std::error_code ec;
    if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
      problem = fmt::format("-o {}: not a directory", out_dir);
    else if (restart && !std::filesystem::is_directory(out_dir, ec))
      problem = fmt::format("no analysis to continue in {}: no such directory", out_dir);
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
    else if (const auto run = run_files_in(out_dir, {}); !run.empty())
      problem = fmt::format("{} holds a run ({}), not an analysis: an analysis's files would lie beside it; choose "
                            "another directory with -o",
                            out_dir, run.front().string());
    else if (restart) {
      try {  // a failure here is every rank's, through first_failure below
        earlier = read_table(out_dir, problem);
        if (problem.empty()) problem = continue_earlier(out_dir, config, limit, earlier, notes);
      } catch (const std::exception& e) {
        problem = e.what();
      }
    } else if (const auto found = analysis_files_in(out_dir); !found.empty()) {
      if (!overwrite)
        problem = fmt::format("{} holds an earlier analysis ({}): continue it with --restart, replace it with "
                              "--overwrite, or choose another directory with -o",
                              out_dir, found.front().string());
      else if (problem = set_aside_run(out_dir, found); problem.empty())
        set_aside = true;
    }
  }
  if (auto text = first_failure(PETSC_COMM_WORLD, problem); !text.empty()) throw CaseError(text);
  if (restart) earlier = shared_trials(PETSC_COMM_WORLD, earlier);
  std::vector<std::string> advice;  // warnings on the case's choices, which a failure may come from
  if (rank == 0) {
    fmt::print("granflow: factor of safety of {} by strength reduction (C / F, tan(phi) / F), each trial to t = {} s, "
               "output in {}{}\n",
               config.title, config.time.end, out_dir,
               restart ? fmt::format(", continuing the analysis there ({} trial{} finished)", earlier.size(),
                                     earlier.size() == 1 ? "" : "s")
                       : std::string());
    for (const auto& note : notes) fmt::print("{}\n", note);
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
  // The table: the trials of this search, then those of the earlier analysis it has not reached (a
  // search continued to a coarser tolerance), which stay in their directories.
  auto table = [&](const std::vector<StrengthTrial>& visited) {
    std::vector<StrengthTrial> rows = visited;
    for (const auto& e : earlier)
      if (std::none_of(visited.begin(), visited.end(), [&](const StrengthTrial& t) { return t.factor == e.factor; }))
        rows.push_back(e);
    write_table(std::filesystem::path(out_dir) / table_name, rows);
  };
  try {
    r = factor_of_safety(
        PETSC_COMM_WORLD, config, out_dir, settings,
        [&](const StrengthTrial& t) {
          if (rank != 0) return;
          under_way();
          finished.push_back(t);
          table(finished);
          fmt::print("F = {}: {} (largest displacement {:.3g} m at t = {:.4g} s; {} steps{}, {:.1f} s{})\n", t.factor,
                     t.diverged ? "fails (diverged)" : t.fails ? "fails" : "stands", t.largest_displacement, t.time,
                     t.steps,
                     t.unconverged_steps > 0 ? fmt::format(", {} of them unconverged", t.unconverged_steps) : std::string(),
                     t.wall_seconds, t.earlier ? "; from the earlier analysis" : "");
          std::fflush(stdout);
        },
        earlier);
  } catch (...) {
    if (set_aside) {  // the new analysis's trials go, and the earlier one comes back
      std::error_code ec;
      for (const auto& p : analysis_files_in(out_dir)) std::filesystem::remove_all(p, ec);
      restore_set_aside_run(out_dir, {});
    }
    throw;
  }
  under_way();  // a search of no trial
  if (rank == 0) table(r.trials);
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
    // A soil near its limit moves slowly: a failing trial of the bracket that failed late, or a standing
    // one that moved a good part of the limit, says that time.end, not the strength, may have decided
    // the bracket. More time can only make more trials fail, so the factor is then an upper bound.
    std::vector<std::string> late;
    for (const auto& t : r.trials) {
      if (t.factor == r.fails_at && t.fails && !t.diverged && t.time > 0.5 * config.time.end)
        late.push_back(fmt::format("the trial at F = {} failed only at t = {:.3g} s", t.factor, t.time));
      if (t.factor == r.stands_at && !t.fails && t.largest_displacement > 0.1 * t.displacement_limit)
        late.push_back(fmt::format("the trial at F = {} stood having moved {:.3g} m, {:.0f} % of the limit", t.factor,
                                   t.largest_displacement, 100.0 * t.largest_displacement / t.displacement_limit));
    }
    if (!late.empty())
      fmt::print("note: time.end = {} s may have decided the bracket: {}; with more time trials nearer the limit may "
                 "fail too, so the factor may be lower (a longer time.end tells)\n",
                 config.time.end, fmt::join(late, ", and "));
  }
  return 0;
}

}  // namespace granflow

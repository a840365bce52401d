// granflow: the command line.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fcntl.h>
#include <unistd.h>
#include <petscsys.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "io/case_advice.hpp"
#include "io/case_error.hpp"
#include "io/case_file.hpp"
#include "io/checkpoint.hpp"
#include "io/collective_failure.hpp"
#include "io/run_directory.hpp"
#include "io/run_lock.hpp"
#include "models/rheology/element_test.hpp"
#include "solver/linear_solver.hpp"
#include "solver/simulation.hpp"

namespace {

// The solvers' method names, checked by PETSc itself (which must be initialised).
void check_solver_methods(const granflow::CaseConfig& c) {
  const std::pair<const char*, const granflow::LinearSolverSettings*> solvers[] = {
      {"momentum", &c.flow.momentum_solver}, {"pressure", &c.flow.pressure_solver}, {"coupled", &c.flow.coupled_solver}};
  for (const auto& [name, settings] : solvers)
    if (auto problem = granflow::unknown_method(*settings); !problem.empty())
      throw granflow::CaseError(fmt::format("{}: solver.{}.{}", c.source.string(), name, problem));
}

int run_case(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
             bool restart, bool overwrite) {
  using namespace granflow;
  CaseConfig config = load_case(case_file, overrides);
  check_solver_methods(config);
  if (out_dir.empty()) out_dir = (std::filesystem::path("out") / std::filesystem::path(case_file).stem()).string();
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // Checked before the simulation makes the output directory, so a mistyped one is not left behind.
  // Every rank sees the same files here (the output directory is shared), so all stop alike. An
  // output directory that cannot be made or written into is the simulation's to report, as it makes it.
  // The run's files under it are up to some 250 characters long (a line sample's, while written):
  // the whole path must stay within the system's PATH_MAX of 4096, or the first checkpoint would fail.
  if (out_dir.size() > 3800)
    throw CaseError(fmt::format("-o: the output directory's path is {} characters long, more than 3800 (the run's "
                                "files under it would pass the system's limit of 4096)", out_dir.size()));
  if (restart && !std::filesystem::exists(out_dir))
    throw CheckpointError(fmt::format("no checkpoint to restart from in {}: no such directory", out_dir));
  {
    std::error_code ec;
    if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
      throw CaseError(fmt::format("-o {}: not a directory", out_dir));
  }
  // One run at a time in a directory (io/run_lock.hpp): taken here where the directory exists, so that
  // a second run is told so rather than that the directory holds an earlier run, and below where the
  // simulation has just made it. Rank 0 holds it for the whole run.
  RunLock lock;
  auto take_lock = [&] {
    const std::string problem = rank == 0 ? lock.take(out_dir) : std::string();
    if (auto text = first_failure(PETSC_COMM_WORLD, problem); !text.empty()) throw CaseError(text);
  };
  if (std::filesystem::is_directory(out_dir)) take_lock();
  if (const auto aside = set_aside_run_in(out_dir); !aside.empty())
    throw CaseError(fmt::format("{} holds {}, the files of an earlier run that a run with --overwrite set aside and "
                                "was stopped before its first step: move them back into {} (or remove {}), then "
                                "run again",
                                out_dir, aside.string(), out_dir, aside.string()));
  const auto earlier = run_files_in(out_dir, config.output.lines);
  if (!restart && !overwrite && !earlier.empty()) {
    std::error_code ec;
    // As read_checkpoint finds one: checkpoint/, or checkpoint.old/ left by a run killed while it wrote.
    const bool resumable = std::filesystem::exists(std::filesystem::path(out_dir) / "checkpoint" / "run.txt", ec) ||
                           std::filesystem::exists(std::filesystem::path(out_dir) / "checkpoint.old" / "run.txt", ec);
    throw CaseError(fmt::format("{} holds an earlier run ({}): {}replace it with --overwrite, or choose another "
                                "directory with -o",
                                out_dir, earlier.front().string(), resumable ? "continue it with --restart, " : ""));
  }
  Simulation sim(PETSC_COMM_WORLD, config, out_dir);  // checks what the case file alone cannot
  take_lock();
  // Only now, with the case found good, every file of the earlier run goes: its checkpoint above all
  // (a later --restart would continue that run), and its later outputs, which the new run might not
  // write again. They are set aside until the new run has taken its first step, and put back if it
  // fails before (run_directory.hpp).
  const bool replacing = overwrite && !restart;
  if (replacing) {  // on every rank alike (a collective call); the files are rank 0's to move
    const std::string problem = rank == 0 && !earlier.empty() ? set_aside_run(out_dir, earlier) : std::string();
    if (auto text = first_failure(PETSC_COMM_WORLD, problem); !text.empty()) throw CaseError(text);
  }
  if (restart) {
    sim.restart();
    if (rank == 0) remove_left_over_files(out_dir, config.output.lines);
  }
  if (rank == 0)
    fmt::print("granflow: {} on {} x {} cells {}to t = {} s, output in {}\n", config.title, config.mesh.cells[0],
               config.mesh.cells[1], restart ? fmt::format("from the checkpoint at t = {:.6g} s ", sim.time()) : "",
               config.time.end, out_dir);
  if (rank == 0)
    for (const auto& line : case_advice(config)) fmt::print(stderr, "warning: {}\n", line);
  std::fflush(stdout);  // the banner is there even if the run is killed (stdout is buffered into a file)
  bool under_way = !replacing;
  RunSummary s;
  try {
    s = sim.run([&](Simulation&, double) {
      if (under_way) return;
      under_way = true;
      if (rank == 0) discard_set_aside_run(out_dir);
    });
  } catch (...) {
    if (!under_way && rank == 0) restore_set_aside_run(out_dir, config.output.lines);
    throw;
  }
  if (!under_way && rank == 0) discard_set_aside_run(out_dir);  // a run of no step (already at time.end)
  if (rank == 0) {
    fmt::print("done: t = {:.6g} s in {} steps ({} taken again with a smaller step), {:.2f} s wall ({:.3g} cell-steps/s){}\n",
               s.time, s.steps, s.retried_steps, s.wall_seconds, double(sim.grid().cell_count()) * s.steps / s.wall_seconds,
               s.reached_steady_state   ? ", steady state reached"
               : s.stopped_at_max_steps ? fmt::format(", stopped at time.max_steps = {} before time.end = {} s",
                                                      sim.config().time.max_steps, sim.config().time.end)
                                        : std::string());
    fmt::print("outer iterations {} ({} of {} steps stopped at numerics.outer_iterations, not at outer_tolerance), "
               "momentum iterations {}, pressure solves {} ({:.1f} iterations each)\n",
               s.outer_iterations, s.steps_outer_unconverged, s.steps, s.momentum_iterations, s.pressure_solves,
               s.pressure_solves ? double(s.pressure_iterations) / s.pressure_solves : 0.0);
    if (s.solves_at_iteration_limit > 0)
      fmt::print("warning: {} linear solves stopped at their solver's max_iterations before its rtol; the face fluxes "
                 "carry their residual (check the soil volume in history.csv)\n",
                 s.solves_at_iteration_limit);
  }
  return 0;
}

// Options given to PETSc that nothing read (a misspelt name, a solver prefix that does not exist),
// one warning each on rank 0: PETSc itself ignores them silently.
void warn_unused_petsc_options(int rank) {
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  PetscOptionsLeftGet(nullptr, &n, &names, &values);
  // Read only by PetscFinalize, after this check.
  constexpr std::string_view at_finalize[] = {"options_view", "options_left", "memory_view",
                                              "malloc_dump",  "malloc_view",  "objects_dump"};
  if (rank == 0)
    for (PetscInt k = 0; k < n; ++k)
      if (std::find(std::begin(at_finalize), std::end(at_finalize), std::string_view(names[k])) == std::end(at_finalize) &&
          !granflow::is_default_petsc_option(names[k]))
        fmt::print(stderr, "warning: PETSc option -{} was given but not used (misspelt, or no such solver)\n", names[k]);
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
}

// PETSc's errors as one line, where PETSc would print its whole trace: the first report of an error
// (PETSC_ERROR_INITIAL) is printed, the frames it passes through on its way up are not. Every such
// error ends the run (the calls that may fail and are handled push PETSc's quiet handler over this
// one), so a single process exits here, before an abort adds Open MPI's banner; several ranks abort
// here, with status 1 whatever PETSc's error code.
// Running out of memory while the grid is made is the common case. GRANFLOW_PETSC_TRACE=1 keeps
// PETSc's own trace.
PetscErrorCode one_line_petsc_error(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                                    PetscErrorType type, const char* message, void*) {
  if (type != PETSC_ERROR_INITIAL) return code;
  const bool memory = code == PETSC_ERR_MEM || std::string_view(function) == "PetscMallocAlign";
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::string what = memory ? "out of memory (a coarser mesh may do)"
                            : text ? text : "error";
  if (!memory && message && *message && std::string_view(message) != what) what += fmt::format(": {}", message);
  int world_size = 1, world_rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  // Most such errors (an option value PETSc does not know) are met by every rank at once: the other
  // ranks wait, so that rank 0's abort stops them before they say it again. An error of one rank
  // alone is still reported, by that rank, half a second later.
  if (world_rank > 0) std::this_thread::sleep_for(std::chrono::milliseconds(500));
  fmt::print(stderr, "error: PETSc: {} (PETSc error {} in {}, {}:{}){}\n", what, int(code), function, file, line,
             world_rank > 0 ? fmt::format(" (rank {})", world_rank) : "");
  std::fflush(stderr);
  if (world_size == 1) std::_Exit(1);
  MPI_Abort(MPI_COMM_WORLD, 1);  // the status of README's "Exit status", not PETSc's error code
  return code;
}

// PETSc stops inside PetscInitialize, with its error trace, on an options file it cannot read, and
// finds a -log_view file it cannot write only at the end of the run: say which, in one line, before
// anything runs. Empty when every such file among the --petsc words can be used.
std::string unusable_petsc_file(const std::vector<std::string>& words) {
  for (size_t k = 0; k < words.size(); ++k) {
    if (words[k] == "-log_view" && k + 1 < words.size() && words[k + 1][0] != '-') {
      // [type]:file[:format]: a file named where the viewer's type ends
      const std::string& viewer = words[k + 1];
      const size_t colon = viewer.find(':');
      if (colon == std::string::npos) continue;
      const std::string file = viewer.substr(colon + 1, viewer.find(':', colon + 1) - colon - 1);
      if (file.empty()) continue;
      const std::filesystem::path path(file);
      const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
      std::error_code ec;
      const bool writable = std::filesystem::exists(path, ec) ? !std::filesystem::is_directory(path, ec) &&
                                                                     access(file.c_str(), W_OK) == 0
                                                               : std::filesystem::is_directory(dir, ec) &&
                                                                     access(dir.c_str(), W_OK) == 0;
      if (!writable) return fmt::format("--petsc -log_view {}: cannot write {}", viewer, file);
      continue;
    }
    if (words[k] != "-options_file" && words[k] != "-options_file_yaml") continue;
    if (k + 1 == words.size()) return fmt::format("--petsc {}: names no file", words[k]);
    const std::string& file = words[k + 1];
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec) || !std::ifstream(file).good())
      return fmt::format("--petsc {}: cannot read {}", words[k], file);
  }
  return {};
}

// Errors every rank meets alike (the case, the mesh on these ranks, the checkpoint's agreed verdict,
// the global speed): rank 0 reports them, and the exit status is returned (README, "Exit status");
// 0 for any other error, which may be one rank's alone.
int report_shared_error(const std::exception& e, const std::string& case_file, int rank) {
  auto report = [&](const std::string& text, int status) {
    if (rank == 0) fmt::print(stderr, "error: {}\n", text);
    return status;
  };
  if (dynamic_cast<const granflow::CaseError*>(&e)) return report(e.what(), 2);
  if (dynamic_cast<const granflow::GridError*>(&e)) return report(fmt::format("{}: {}", case_file, e.what()), 2);
  if (dynamic_cast<const granflow::CheckpointError*>(&e)) return report(e.what(), 1);
  if (dynamic_cast<const granflow::DivergenceError*>(&e)) return report(e.what(), 3);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Started with stdout closed (`>&-`), the first file MPI opens would take descriptor 1, and the
  // progress lines would be written into it, or fail at the end: give stdout to /dev/null instead.
  if (fcntl(STDOUT_FILENO, F_GETFD) == -1 && errno == EBADF) {
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0 && null != STDOUT_FILENO) {
      dup2(null, STDOUT_FILENO);
      close(null);
    }
  }
  CLI::App app{"granflow: dense granular flows as a two-phase visco-plastic continuum"};
  app.require_subcommand(1);
  std::string case_file, out_dir;
  std::vector<std::string> overrides;
  std::vector<std::string> petsc_options;
  bool restart = false, overwrite = false;

  auto* run = app.add_subcommand("run", "run a case");
  run->add_option("case", case_file, "case file (TOML)")->required();
  run->add_option("-o,--output", out_dir, "output directory (default out/<case name>)");
  run->add_option("--set", overrides, "override a case key: KEY=VALUE (repeatable)")->allow_extra_args(false);
  run->add_option("--petsc", petsc_options, "options passed to PETSc, e.g. --petsc=-pressure_ksp_monitor")
      ->allow_extra_args(false);
  auto* restart_flag = run->add_flag("--restart", restart,
                "continue from the checkpoint in the output directory (written at each output time; same case, "
                "mesh and number of ranks)");
  run->add_flag("--overwrite", overwrite, "replace an earlier run in the output directory (refused without it)")
      ->excludes(restart_flag);

  auto* check = app.add_subcommand("check", "validate a case file without running it");
  check->add_option("case", case_file, "case file (TOML)")->required();
  check->add_option("--set", overrides, "override a case key: KEY=VALUE (repeatable)")->allow_extra_args(false);
  check->add_option("--petsc", petsc_options,
                    "the run's PETSc options, so that a run's command line can be checked as it is (their form and "
                    "options files are checked; their values when a run builds its solvers)")
      ->allow_extra_args(false);

  double phi_deg = 36.5;
  bool csv = false;
  auto* element = app.add_subcommand("element-test",
                                     "print the element test of the yield-surface viscosities (Table 1 of Rauter et al. 2020)");
  element->add_option("--phi", phi_deg, "friction angle in degrees")->check(CLI::Range(0.001, 89.999));
  element->add_flag("--csv", csv, "print CSV instead of a table");

  // CLI11 would say only that a subcommand is required.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string command = argv[1];
    if (command != "run" && command != "check" && command != "element-test") {
      fmt::print(stderr, "error: unknown command '{}' (the commands are run, check and element-test; see granflow --help)\n",
                 command);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's message (or the help, status 0); a command line it refuses is status 2, as a case is.
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (run->count("--output") && out_dir.empty()) {
    fmt::print(stderr, "error: -o/--output: the output directory is empty\n");
    return 2;
  }
  for (const auto& o : petsc_options)
    if (o.empty() || o[0] != '-') {
      fmt::print(stderr, "error: --petsc '{}': PETSc options start with '-', e.g. --petsc=\"-coupled_ksp_monitor\"\n", o);
      return 2;
    }

  if (*element) {
    try {
      fmt::print("{}", granflow::rheology::format_element_test(phi_deg, csv));
      return 0;
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return 2;
    }
  }

  // PETSc sees only the options given through --petsc (and PETSC_OPTIONS from the environment), as
  // its command line, so that those read at start-up (-log_view, -info, -malloc_debug) work too.
  // Each --petsc is split at blanks; values cannot be quoted.
  std::vector<std::string> petsc_words;
  for (const auto& o : petsc_options) {
    std::istringstream words(o);
    for (std::string w; words >> w;) petsc_words.push_back(w);
  }
  // MPI is started before PETSc, so that rank 0 alone checks what PETSc would read on rank 0 alone
  // (its options files) and every rank stops with it. PetscFinalize then leaves MPI_Finalize to us.
  MPI_Init(&argc, &argv);
  {
    int world_rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    std::string problem = world_rank == 0 ? unusable_petsc_file(petsc_words) : std::string();
    int failed = problem.empty() ? 0 : 1;
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (failed) {
      if (world_rank == 0) fmt::print(stderr, "error: {}\n", problem);
      MPI_Finalize();
      return 2;
    }
  }
  std::vector<char*> petsc_argv{argv[0]};
  for (auto& w : petsc_words) petsc_argv.push_back(w.data());
  petsc_argv.push_back(nullptr);
  int pargc = static_cast<int>(petsc_argv.size()) - 1;
  char** pargv = petsc_argv.data();
  if (PetscInitialize(&pargc, &pargv, nullptr, nullptr) != 0) {
    int world_rank = 0, world_size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
    if (world_rank == 0) fmt::print(stderr, "error: PETSc could not start (its message is above)\n");
    if (world_size > 1) MPI_Abort(MPI_COMM_WORLD, 2);  // PETSc may have failed on one rank alone
    MPI_Finalize();
    return 2;
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (const char* trace = std::getenv("GRANFLOW_PETSC_TRACE"); !trace || std::string_view(trace) != "1")
    PetscPushErrorHandler(one_line_petsc_error, nullptr);

  if (*check) {
    int status = 0;
    try {
      const auto c = granflow::load_case(case_file, overrides);
      check_solver_methods(c);
      // What the case file alone cannot tell (the mesh's layout on these ranks, initial shapes that
      // miss every cell's samples) is found where a run finds it: in laying out the initial state.
      const auto laid_out = granflow::check_initial_state(PETSC_COMM_WORLD, c);
      if (rank == 0) {  // every rank checks the same file alike; one says so
        std::string placed;
        if (c.soil)
          placed += fmt::format("; initial soil {:.6g} {}", laid_out.soil_volume,
                                c.mesh.axisymmetric ? "m^3 per radian" : "m^2 per metre of depth");
        if (!c.obstacles.empty()) placed += fmt::format("; {} cells blocked by obstacles", laid_out.blocked_cells);
        fmt::print("{}: valid ({} x {} cells, t_end = {} s{})\n", case_file, c.mesh.cells[0], c.mesh.cells[1], c.time.end,
                   placed);
        for (const auto& line : granflow::case_advice(c)) fmt::print(stderr, "warning: {}\n", line);
      }
    } catch (const std::exception& e) {
      status = report_shared_error(e, case_file, rank);
      if (status == 0) throw;
    }
    PetscFinalize();
    MPI_Finalize();
    return status;
  }

  // These errors are met by every rank alike (the case, the checkpoint's agreed verdict, the global
  // speed), so rank 0 reports them and all ranks stop in order. Any other error may be one rank's
  // alone while the others wait in a collective call: that rank reports it and stops them all.
  int status = 0;
  try {
    status = run_case(case_file, overrides, out_dir, restart, overwrite);
    warn_unused_petsc_options(rank);
  } catch (const std::exception& e) {
    status = report_shared_error(e, case_file, rank);
    if (status == 0) {
      // As for PETSc's errors: one that every rank meets (a full disk under every rank's checkpoint
      // file) is said by rank 0, whose abort stops the others while they wait.
      if (rank > 0) std::this_thread::sleep_for(std::chrono::milliseconds(500));
      fmt::print(stderr, "error: {}{}\n", e.what(), rank > 0 ? fmt::format(" (rank {})", rank) : "");
      if (size > 1) MPI_Abort(PETSC_COMM_WORLD, 1);
      status = 1;
    }
  }
  PetscFinalize();
  MPI_Finalize();
  return status;
}

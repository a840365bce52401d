// granflow: the command line.
#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <petscsys.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string_view>
#include <string>
#include <vector>

#include "app/petsc_messages.hpp"
#include "app/run_case.hpp"
#include "app/run_stability.hpp"
#include "io/case_advice.hpp"
#include "io/case_error.hpp"
#include "io/case_file.hpp"
#include "io/checkpoint.hpp"
#include "models/rheology/element_test.hpp"
#include "solver/divergence_error.hpp"
#include "solver/flow_settings.hpp"
#include "solver/solver_options_check.hpp"
#include "solver/out_of_memory_error.hpp"
#include "solver/simulation.hpp"

namespace {

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
  if (dynamic_cast<const granflow::OutOfMemoryError*>(&e)) return report(e.what(), 1);
  return 0;
}

// Whether this process is the first (or only) one of its launch, from the launcher's environment:
// the command line is checked before MPI starts, so under mpirun every rank would say the same.
bool first_of_launch() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* rank = std::getenv(name)) return std::string_view(rank) == "0";
  return true;
}

// A number within [low, high] (a finite one: CLI11's ranges let "nan" through, as no comparison
// with it fails), with a message that says so in the range's own terms.
CLI::Validator finite_in(double low, double high, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || value < low || value > high)
          return fmt::format("'{}' is not {}", text, what);
        return {};
      },
      what, "");
}

// Started with stdin, stdout or stderr closed (`>&-`), the first file MPI opens would take the
// descriptor, and the progress lines or warnings would be written into it, or fail: give each
// closed one to /dev/null instead.
void give_closed_standard_streams_to_dev_null() {
  for (int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO})
    if (fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
      const int null = open("/dev/null", fd == STDIN_FILENO ? O_RDONLY : O_WRONLY);
      if (null >= 0 && null != fd) {
        dup2(null, fd);
        close(null);
      }
    }
}

// Starts MPI, then PETSc with the options of --petsc as its command line; 0, or the exit status of a
// start that failed (its message said).
int start_mpi_and_petsc(int& argc, char**& argv, const std::vector<std::string>& petsc_options, bool petsc_trace) {
  // PETSc sees only the options given through --petsc (and PETSC_OPTIONS from the environment), as
  // its command line, so that those read at start-up (-log_view, -info, -malloc_debug) work too.
  // Each --petsc is split at blanks; values cannot be quoted.
  static std::vector<std::string> petsc_words;  // PETSc keeps the arguments it was started with
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
    std::string problem;
    if (world_rank == 0) {
      problem = granflow::unusable_petsc_file(petsc_words);
      if (const char* env = std::getenv("PETSC_OPTIONS"); env && problem.empty()) {  // read by PETSc as well
        std::vector<std::string> env_words;
        std::istringstream words(env);
        for (std::string w; words >> w;) env_words.push_back(w);
        problem = granflow::unusable_petsc_file(env_words, "PETSC_OPTIONS");
      }
    }
    int failed = problem.empty() ? 0 : 1;
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (failed) {
      if (world_rank == 0) fmt::print(stderr, "error: {}\n", problem);
      MPI_Finalize();
      return 2;
    }
  }
  static std::vector<char*> petsc_argv;
  petsc_argv = {argv[0]};
  for (auto& w : petsc_words) petsc_argv.push_back(w.data());
  petsc_argv.push_back(nullptr);
  int pargc = static_cast<int>(petsc_argv.size()) - 1;
  char** pargv = petsc_argv.data();
  if (!petsc_trace) PetscPushErrorHandler(granflow::granflow_petsc_error, nullptr);
  if (PetscInitialize(&pargc, &pargv, nullptr, nullptr) != 0) {
    int world_rank = 0, world_size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
    const std::string& why = granflow::startup_petsc_error_text();
    if (world_rank == 0)
      fmt::print(stderr, "error: PETSc could not start{}\n", why.empty() ? " (its message is above)" : ": " + why);
    if (world_size > 1) MPI_Abort(MPI_COMM_WORLD, 2);  // PETSc may have failed on one rank alone
    MPI_Finalize();
    return 2;
  }
  return 0;
}

// granflow check: the case laid out as a run lays it out, what it holds said on one line, and the
// warnings on its numerics; the exit status (`fail` gives that of an error).
template <class Fail>
int check_case(const std::string& case_file, const std::vector<std::string>& overrides, int rank, Fail fail) {
  int status = 0;
  try {
    const auto c = granflow::load_case(case_file, overrides);
    granflow::check_solver_options(c);
    // What the case file alone cannot tell (the mesh's layout on these ranks, initial shapes that
    // miss every cell's samples) is found where a run finds it: in laying out the initial state.
    const auto laid_out = granflow::check_initial_state(PETSC_COMM_WORLD, c);
    if (rank == 0) {  // every rank checks the same file alike; one says so
      std::string placed;
      if (c.soil)
        placed += fmt::format("; initial soil {:.6g} {}{}", laid_out.soil_volume, granflow::volume_unit(c.mesh),
                              c.soil->has_initial_shapes() ? "" : " (an inlet brings the soil)");
      const auto& volumes = laid_out.material_volumes;
      for (size_t k = 0; k < volumes.size(); ++k)
        placed += fmt::format("{}{} {:.6g}", k == 0 ? ", of which " : ", ",
                              k == 0 ? std::string("the rheology's own soil") : c.soil->materials[k - 1].name, volumes[k]);
      if (c.has_obstacles()) {
        placed += fmt::format("; {} cells blocked by obstacles", laid_out.blocked_cells);
        // A shape may reach into an obstacle on purpose (soil laid over terrain); the part inside is
        // left out, and said, so that a shape placed there by mistake is seen.
        if (c.soil && laid_out.soil_in_obstacles > 0.0)
          placed += fmt::format(", which leave out {:.6g} {} of the initial shapes' soil", laid_out.soil_in_obstacles,
                                granflow::volume_unit(c.mesh));
        if (!laid_out.ridges_lowered.empty()) placed += "; " + laid_out.ridges_lowered;
      }
      fmt::print("{}: valid ({} cells, t_end = {} s{})\n", case_file, granflow::cell_counts(c.mesh), c.time.end, placed);
      std::fflush(stdout);  // before the warnings on stderr, also where both go to one file
      for (const auto& line : granflow::case_advice(c)) fmt::print(stderr, "warning: {}\n", line);
    }
    // PETSc's options that the run's solvers would not read, as the run would warn of them at its end.
    const int dimension = c.mesh.dimension();
    const auto left = granflow::options_left_by_solvers(granflow::solvers_made(c.flow, c.mesh.axisymmetric, dimension));
    granflow::warn_unused_petsc_options(rank, &left);
  } catch (const std::exception& e) {
    status = fail(e);
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  give_closed_standard_streams_to_dev_null();
  CLI::App app{"granflow: dense granular flows as a two-phase visco-plastic continuum"};
  app.set_version_flag("--version", fmt::format("granflow {}", GRANFLOW_VERSION));
  app.require_subcommand(1);
  std::string case_file, out_dir;
  std::vector<std::string> overrides;
  std::vector<std::string> petsc_options;
  bool restart = false, overwrite = false;

  auto* run = app.add_subcommand("run", "run a case");
  run->add_option("case", case_file, "case file (TOML)")->required();
  run->add_option("-o,--output", out_dir, "output directory (default out/<case name>)");
  run->add_option("--set", overrides, "override a case key, one KEY=VALUE per --set (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  run->add_option("--petsc", petsc_options,
                  "options passed to PETSc, quoted as one value per --petsc (repeatable), e.g. "
                  "--petsc=\"-pressure_ksp_monitor -log_view\"")
      ->type_name("OPTIONS")
      ->allow_extra_args(false);
  auto* restart_flag = run->add_flag("--restart", restart,
                "continue from the checkpoint in the output directory (written at each output time; same case "
                "and mesh, any number of ranks)");
  run->add_flag("--overwrite", overwrite, "replace an earlier run in the output directory (refused without it)")
      ->excludes(restart_flag);

  granflow::StrengthReductionSettings strength;
  auto* stability = app.add_subcommand(
      "stability", "factor of safety by strength reduction: the case run with C / F and tan(phi) / F, F bisected "
                   "between standing and failing within time.end");
  stability->add_option("case", case_file, "case file (TOML)")->required();
  stability->add_option("-o,--output", out_dir, "output directory (default out/<case name>_stability)");
  stability->add_option("--set", overrides, "override a case key, one KEY=VALUE per --set (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  stability->add_option("--petsc", petsc_options, "options passed to PETSc, as for run")
      ->type_name("OPTIONS")
      ->allow_extra_args(false);
  stability->add_option("--first", strength.first_factor, "the first factor tried (default 1)")
      ->check(finite_in(0.01, 100.0, "a number from 0.01 to 100"));
  stability->add_option("--tolerance", strength.tolerance, "bisect until the factors that stand and fail are this close (default 0.01)")
      ->check(finite_in(1e-4, 10.0, "a number from 0.0001 to 10"));
  stability->add_option("--displacement", strength.displacement_limit,
                        "the soil fails when it moves further than this, m (default: a tenth of the smallest cell)")
      ->check(finite_in(1e-12, 1e12, "a length from 1e-12 to 1e12 m"));
  auto* stability_restart = stability->add_flag(
      "--restart", restart,
      "continue the earlier analysis in the output directory (same case, --set and --displacement): its finished "
      "trials are taken as they are; --tolerance may be finer");
  stability->add_flag("--overwrite", overwrite, "replace an earlier analysis in the output directory")
      ->excludes(stability_restart);

  auto* check = app.add_subcommand("check", "validate a case file without running it");
  check->add_option("case", case_file, "case file (TOML)")->required();
  check->add_option("--set", overrides, "override a case key, one KEY=VALUE per --set (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  check->add_option("--petsc", petsc_options,
                    "the run's PETSc options, so that a run's command line can be checked as it is (their form, "
                    "options files and the solvers' options are checked, and options no solver would read are warned of; monitors and viewers are the run's)")
      ->type_name("OPTIONS")
      ->allow_extra_args(false);

  double phi_deg = 36.5;
  bool csv = false;
  auto* element = app.add_subcommand("element-test",
                                     "print the element test of the yield-surface viscosities (Table 1 of Rauter et al. 2020)");
  element->add_option("--phi", phi_deg, "friction angle in degrees (default 36.5, the paper's)")->check(finite_in(0.001, 89.999, "an angle from 0.001 to 89.999 degrees"));
  element->add_flag("--csv", csv, "print CSV instead of a table");

  // Errors of the command line, said by the first process of a launch alone.
  const bool first = first_of_launch();
  std::ostream silent(nullptr);
  auto refuse = [&](const std::string& text) {
    if (first) fmt::print(stderr, "error: {}\n", text);
    return 2;
  };
  // CLI11 would say only that a subcommand is required.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string command = argv[1];
    if (command != "run" && command != "check" && command != "stability" && command != "element-test")
      return refuse(fmt::format("unknown command '{}' (the commands are run, check, stability and element-test; see "
                                "granflow --help)",
                                command));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // The help or the version (status 0) as CLI11 writes them; a command line it refuses is one error
    // line, as other bad input, and status 2, as a case is.
    if (e.get_exit_code() == 0) return app.exit(e, first ? std::cout : silent, first ? std::cerr : silent);
    // The help to see is the command's, which lists its options; arguments it does not take are named in
    // the order given (CLI11's message lists them backwards).
    const CLI::App* given = nullptr;
    for (const CLI::App* sub : {run, stability, check, element})
      if (sub->parsed()) given = sub;
    const std::string help = given ? fmt::format("granflow {} --help", given->get_name()) : "granflow --help";
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && given) {
      const auto extra = given->remaining();
      std::string said;
      for (const auto& a : extra) said += (said.empty() ? "" : " ") + a;
      const bool output = std::find(extra.begin(), extra.end(), "-o") != extra.end() ||
                          std::find(extra.begin(), extra.end(), "--output") != extra.end();
      return refuse(fmt::format("{} does not take: {}{} (see {})", given->get_name(), said,
                                output && (given == check || given == element) ? "; it writes no output directory" : "",
                                help));
    }
    // An option given more than once: CLI11 says "At Most 1 required but received N".
    std::string what = e.what();
    if (const auto at = what.find("At Most 1 required but received "); at != std::string::npos)
      what = what.substr(0, at) + "given " + what.substr(at + std::string_view("At Most 1 required but received ").size()) +
             " times; give it once";
    return refuse(fmt::format("{} (see {})", what, help));
  }
  if ((run->count("--output") || stability->count("--output")) && out_dir.empty())
    return refuse("-o/--output: the output directory is empty");
  for (const auto& o : petsc_options)
    if (o.empty() || o[0] != '-')
      return refuse(fmt::format("--petsc '{}': PETSc options start with '-', e.g. --petsc=\"-coupled_ksp_monitor\"", o));

  if (*element) {
    try {
      fmt::print("{}", granflow::rheology::format_element_test(phi_deg, csv));
      return 0;
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return 2;
    }
  }

  const bool petsc_trace = [] {
    const char* trace = std::getenv("GRANFLOW_PETSC_TRACE");
    return trace && std::string_view(trace) == "1";
  }();
  if (const int status = start_mpi_and_petsc(argc, argv, petsc_options, petsc_trace); status != 0) return status;
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  granflow::petsc_has_started();  // PETSc's errors from here on end the run with one line

  // Errors met by every rank alike (the case, the checkpoint's agreed verdict, the global speed):
  // rank 0 reports them and all ranks stop in order. Any other error may be one rank's alone while the
  // others wait in a collective call: that rank reports it (once, if every rank meets it, as a full
  // disk under every rank's checkpoint file) and stops them all.
  auto fail = [&](const std::exception& e) {
    if (const int shared = report_shared_error(e, case_file, rank); shared != 0) return shared;
    granflow::say_error_once(e.what());
    if (size > 1) MPI_Abort(PETSC_COMM_WORLD, 1);
    return 1;
  };

  if (*check) {
    const int status = check_case(case_file, overrides, rank, fail);
    PetscFinalize();
    MPI_Finalize();
    return status;
  }

  int status = 0;
  try {
    status = *stability ? granflow::run_stability(case_file, overrides, out_dir, overwrite, restart, strength)
                        : granflow::run_case(case_file, overrides, out_dir, restart, overwrite);
    granflow::warn_unused_petsc_options(rank);
  } catch (const std::exception& e) {
    status = fail(e);
  }
  PetscFinalize();
  MPI_Finalize();
  return status;
}

// granflow: the command line.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <petscsys.h>

#include <filesystem>

#include "io/case_error.hpp"
#include "io/case_file.hpp"
#include "io/checkpoint.hpp"
#include "models/rheology/element_test.hpp"
#include "solver/simulation.hpp"

namespace {

int run_case(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
             bool restart) {
  using namespace granflow;
  CaseConfig config = load_case(case_file, overrides);
  if (out_dir.empty()) out_dir = (std::filesystem::path("out") / std::filesystem::path(case_file).stem()).string();
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // Checked before the simulation makes the output directory, so a mistyped one is not left behind.
  if (restart && !std::filesystem::exists(out_dir))
    throw CheckpointError(fmt::format("no checkpoint to restart from in {}: no such directory", out_dir));
  Simulation sim(PETSC_COMM_WORLD, config, out_dir);
  if (restart) sim.restart();
  if (rank == 0)
    fmt::print("granflow: {} on {} x {} cells {}to t = {} s, output in {}\n", config.title, config.mesh.cells[0],
               config.mesh.cells[1], restart ? fmt::format("from the checkpoint at t = {:.6g} s ", sim.time()) : "",
               config.time.end, out_dir);
  const RunSummary s = sim.run();
  if (rank == 0) {
    fmt::print("done: t = {:.6g} s in {} steps ({} taken again with a smaller step), {:.2f} s wall ({:.3g} cell-steps/s){}\n",
               s.time, s.steps, s.retried_steps, s.wall_seconds, double(sim.grid().cell_count()) * s.steps / s.wall_seconds,
               s.reached_steady_state ? ", steady state reached" : "");
    fmt::print("outer iterations {}, momentum iterations {}, pressure solves {} ({:.1f} iterations each)\n",
               s.outer_iterations, s.momentum_iterations, s.pressure_solves,
               s.pressure_solves ? double(s.pressure_iterations) / s.pressure_solves : 0.0);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"granflow: dense granular flows as a two-phase visco-plastic continuum"};
  app.require_subcommand(1);
  std::string case_file, out_dir;
  std::vector<std::string> overrides;
  std::vector<std::string> petsc_options;
  bool restart = false;

  auto* run = app.add_subcommand("run", "run a case");
  run->add_option("case", case_file, "case file (TOML)")->required();
  run->add_option("-o,--output", out_dir, "output directory (default out/<case name>)");
  run->add_option("--set", overrides, "override a case key: KEY=VALUE (repeatable)");
  run->add_option("--petsc", petsc_options, "options passed to PETSc, e.g. --petsc=-pressure_ksp_monitor");
  run->add_flag("--restart", restart,
                "continue from the checkpoint in the output directory (written at each output time; same case, "
                "mesh and number of ranks)");

  auto* check = app.add_subcommand("check", "validate a case file without running it");
  check->add_option("case", case_file, "case file (TOML)")->required();
  check->add_option("--set", overrides, "override a case key: KEY=VALUE (repeatable)");

  double phi_deg = 36.5;
  bool csv = false;
  auto* element = app.add_subcommand("element-test",
                                     "print the element test of the yield-surface viscosities (Table 1 of Rauter et al. 2020)");
  element->add_option("--phi", phi_deg, "friction angle in degrees")->check(CLI::Range(0.001, 89.999));
  element->add_flag("--csv", csv, "print CSV instead of a table");

  CLI11_PARSE(app, argc, argv);

  if (*element) {
    try {
      fmt::print("{}", granflow::rheology::format_element_test(phi_deg, csv));
      return 0;
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return 2;
    }
  }

  if (*check) {
    try {
      const auto c = granflow::load_case(case_file, overrides);
      fmt::print("{}: valid ({} x {} cells, t_end = {} s)\n", case_file, c.mesh.cells[0], c.mesh.cells[1], c.time.end);
      return 0;
    } catch (const granflow::CaseError& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return 2;
    }
  }

  // PETSc sees only the options given through --petsc (and PETSC_OPTIONS from the environment).
  int pargc = 1;
  char** pargv = argv;
  PetscInitialize(&pargc, &pargv, nullptr, nullptr);
  for (const auto& o : petsc_options) PetscOptionsInsertString(nullptr, o.c_str());
  int status = 0;
  try {
    status = run_case(case_file, overrides, out_dir, restart);
  } catch (const granflow::CaseError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    status = 2;
  } catch (const granflow::DivergenceError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    status = 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    status = 1;
  }
  PetscFinalize();
  return status;
}

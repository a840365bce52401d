#include "app/run_case.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/peak_memory.hpp"
#include "io/case_advice.hpp"
#include "io/case_error.hpp"
#include "io/checkpoint.hpp"
#include "io/collective_failure.hpp"
#include "io/run_directory.hpp"
#include "io/run_lock.hpp"
#include "solver/divergence_error.hpp"
#include "solver/solver_options_check.hpp"
#include "solver/simulation.hpp"

namespace granflow {

void check_solver_options(const CaseConfig& c) {
  const std::pair<const char*, const LinearSolverSettings*> solvers[] = {
      {"momentum", &c.flow.momentum_solver}, {"pressure", &c.flow.pressure_solver}, {"coupled", &c.flow.coupled_solver}};
  for (const auto& [name, settings] : solvers)
    if (auto problem = unknown_method(*settings); !problem.empty())
      throw CaseError(fmt::format("{}: solver.{}.{}", c.source.string(), name, problem));
  // The solvers the run makes, as it makes them, under PETSc's options.
  const bool coupled = c.flow.numerics.pressure_coupling == PressureCoupling::coupled;
  const bool layers = c.mesh.dimension() == 3;
  const std::pair<const char*, const LinearSolverSettings*> made[] = {
      {"momentum_x", &c.flow.momentum_solver}, {"momentum_y", &c.flow.momentum_solver},
      {"momentum_z", layers ? &c.flow.momentum_solver : nullptr},
      {"pressure", &c.flow.pressure_solver}, {"coupled", coupled ? &c.flow.coupled_solver : nullptr}};
  for (const auto& [prefix, settings] : made)
    if (settings)
      if (auto problem = petsc_options_problem(prefix, *settings); !problem.empty()) throw CaseError(problem);
}

int run_case(const std::string& case_file, const std::vector<std::string>& overrides, std::string out_dir,
             bool restart, bool overwrite) {
  CaseConfig config = load_case(case_file, overrides);
  check_solver_options(config);
  if (out_dir.empty()) out_dir = default_output_directory(case_file, "").string();
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
  if (restart) {
    std::error_code ec;
    if (!std::filesystem::exists(out_dir, ec)) {
      if (ec && ec != std::errc::no_such_file_or_directory)
        throw CaseError(fmt::format("-o {}: {}", out_dir, ec.message()));
      throw CheckpointError(fmt::format("no checkpoint to restart from in {}: no such directory", out_dir));
    }
  }
  {
    std::error_code ec;
    if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
      throw CaseError(fmt::format("-o {}: not a directory", out_dir));
  }
  if (auto problem = inside_a_runs_own_directory(out_dir); !problem.empty()) throw CaseError(problem);
  // One run at a time in a directory (io/run_lock.hpp): taken here if the directory exists, so that
  // a second run is told so rather than that the directory holds an earlier run, and below where the
  // simulation has just made it. Rank 0 alone looks and holds it for the whole run; every rank takes
  // part in both calls alike.
  RunLock lock;
  auto take_lock = [&] {
    std::error_code ec;
    const std::string problem =
        rank == 0 && std::filesystem::is_directory(out_dir, ec) ? lock.take(out_dir) : std::string();
    if (auto text = first_failure(PETSC_COMM_WORLD, problem); !text.empty()) throw CaseError(text);
  };
  take_lock();
  if (const auto aside = set_aside_run_in(out_dir); !aside.empty())
    throw CaseError(fmt::format("{} holds {}, the files of an earlier run that a run with --overwrite set aside and "
                                "was stopped before its first step: move them back into {} (or remove {}), then "
                                "run again",
                                out_dir, aside.string(), out_dir, aside.string()));
  if (const auto analysis = analysis_files_in(out_dir); !analysis.empty())
    throw CaseError(fmt::format("{} holds a stability analysis ({}): a run's files would lie beside it; choose another "
                                "directory with -o",
                                out_dir, analysis.front().string()));
  if (const auto analysis = analysis_of_trial(out_dir); !analysis.empty())
    throw CaseError(fmt::format("{} is a trial of the stability analysis in {}, which a continued analysis reads: "
                                "choose another directory with -o",
                                out_dir, analysis.string()));
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
    fmt::print("granflow: {} on {} cells {}to t = {} s, output in {}\n", config.title, cell_counts(config.mesh),
               restart ? fmt::format("from the checkpoint at t = {:.6g} s ", sim.time()) : "",
               config.time.end, out_dir);
  if (rank == 0 && !sim.ridges_lowered().empty()) fmt::print("obstacles: {}\n", sim.ridges_lowered());
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
  } catch (const DivergenceError& e) {
    if (under_way) throw;
    if (rank == 0) restore_set_aside_run(out_dir, config.output.lines);
    // The new run's first output went with it: what is kept is the earlier run.
    std::string text = e.what();
    if (const auto at = text.find(last_output_kept); at != std::string::npos)
      text.replace(at, std::string_view(last_output_kept).size(),
                   fmt::format("the earlier run's files are put back in {}", out_dir));
    throw DivergenceError(text);
  } catch (...) {
    if (!under_way && rank == 0) restore_set_aside_run(out_dir, config.output.lines);
    throw;
  }
  if (!under_way && rank == 0) discard_set_aside_run(out_dir);  // a run of no step (already at time.end)
  const double peak_bytes = peak_resident_bytes_summed(PETSC_COMM_WORLD);
  if (rank == 0) {
    fmt::print("done: t = {:.6g} s in {} steps ({} taken again with a smaller step), {:.2f} s wall ({:.3g} cell-steps/s){}\n",
               s.time, s.steps, s.retried_steps, s.wall_seconds, double(sim.grid().cell_count()) * s.steps / s.wall_seconds,
               s.reached_steady_state   ? ", steady state reached"
               : s.soil_at_rest         ? fmt::format(", the soil at rest (slower than time.rest_speed = {} m/s everywhere)",
                                                      sim.config().time.rest_speed)
               : s.stopped_at_max_steps ? fmt::format(", stopped at time.max_steps = {} before time.end = {} s",
                                                      sim.config().time.max_steps, sim.config().time.end)
                                        : std::string());
    // A step that takes all its outer iterations is what a fixed count of them (the collapses' two) asks
    // for, not a failure: the line says so rather than calling such steps unconverged.
    const auto& numerics = sim.config().flow.numerics;
    fmt::print("outer iterations {} (numerics.outer_iterations = {}: {} of {} steps took them all, their last change "
               "above outer_tolerance = {:g}), momentum iterations {}, {} solves {} ({:.1f} iterations each)\n",
               s.outer_iterations, numerics.outer_iterations, s.steps_outer_unconverged, s.steps, numerics.outer_tolerance,
               s.momentum_iterations,
               numerics.pressure_coupling == PressureCoupling::coupled ? "coupled (velocity and pressure)" : "pressure",
               s.pressure_solves,
               s.pressure_solves ? double(s.pressure_iterations) / s.pressure_solves : 0.0);
    int ranks = 1;
    MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
    fmt::print("peak memory {:.0f} MB ({})\n", peak_bytes / 1e6,
               ranks == 1 ? std::string("one rank") : fmt::format("summed over {} ranks", ranks));
    if (s.solves_at_iteration_limit > 0)
      fmt::print("warning: {} linear solves stopped at their solver's max_iterations before its rtol; the face fluxes "
                 "carry their residual (check the soil volume in history.csv)\n",
                 s.solves_at_iteration_limit);
    // The volume of fluid conserves the soil to round-off (1e-13 or so) when the face fluxes are
    // divergence-free; inexact solves make and destroy soil, which no other line would show.
    if (!(std::abs(s.soil_balance_error) <= 1e-6))
      fmt::print("warning: the soil's volume, with what left through open sides, changed by {:.3g} % over the run "
                 "(round-off keeps it within 1e-11 %): the linear solves were not exact (solver.coupled, "
                 "solver.pressure: docs/case_file.md)\n",
                 100.0 * s.soil_balance_error);
  }
  return 0;
}

}  // namespace granflow

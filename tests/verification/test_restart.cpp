// Checkpoint and restart: a run stopped between outputs and restarted from its last
// checkpoint ends exactly where the run that was never stopped ends, field by field and row by row
// of the history, on one rank (tests/verification/restart_check.hpp; two ranks: tests/parallel). The collapse takes the numerics
// of the shipped case at Courant 1 (coupled solve, look-ahead viscosity from the last two steps, two
// VoF sweeps, test::bui2008_at_courant_one), so every piece of state a step starts from must come
// back; the cavity has no soil phase.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "restart_check.hpp"
#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow {
namespace {

using test::expect_restart_reproduces;
using test::scratch;

std::string refusal(Simulation& sim);

// Makes a checkpoint one of those written before run.txt ended with the checksums: takes off that
// line, so that a test may alter the files and reach the checks a checksum would come before.
void as_written_before_checksums(const std::filesystem::path& checkpoint) {
  const auto run_txt = checkpoint / "run.txt";
  std::string text = test::file_text(run_txt);
  const size_t at = text.rfind("\nchecksum ");
  ASSERT_NE(at, std::string::npos) << "run.txt has no checksum";
  text.resize(at + 1);
  std::ofstream(run_txt) << text;
}

TEST(Restart, CollapseContinuesExactlyFromItsLastCheckpoint) {
  const double t =
      expect_restart_reproduces("cases/bui2008_experiment.toml",
                                test::bui2008_at_courant_one({"mesh.cells=[60,20]", "time.end=0.3",
                                                              "output.interval=0.1", "output.progress_seconds=0"}),
                                45, true);
  std::printf("collapse restarted from its checkpoint at t = %.3g s\n", t);
}

// A mesh of layers: the quarter sand column of cases/lube2004_a05_3d.toml on cells of 2 cm under its
// coupled solve with an air band and momentum moved with the soil's mass; the checkpoint holds the
// third velocity and displacement components and planes of every layer with their ghosts.
TEST(Restart, AColumnOnAMeshOfLayersContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/lube2004_a05_3d.toml",
      {"mesh.cells=[20,8,20]", "time.end=0.1", "output.times=[0.05]", "output.progress_seconds=0"}, 16, true);
  std::printf("3D column restarted from its checkpoint at t = %.3g s\n", t);
}

// Obstacles on a mesh of layers: the slit barrier of cases/slit_barrier_3d.toml; the checkpoint's
// blocked cells hold their mirrors, which a restart clears and mirrors anew.
TEST(Restart, ASlitBarrierOfLayersContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/slit_barrier_3d.toml", {"time.end=0.02", "output.times=[0.01]", "output.progress_seconds=0"}, 19, true);
  std::printf("3D slit barrier restarted from its checkpoint at t = %.3g s\n", t);
}

// Two soil materials of two densities: their shares are part of the checkpoint.
TEST(Restart, LayeredCollapseContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/bui2008_experiment.toml",
      test::bui2008_at_courant_one({"mesh.cells=[60,20]", "time.end=0.3", "output.interval=0.1",
                                    "output.progress_seconds=0",
                                    "soil.materials=[{name = \"lower\", friction_angle = 10.0, density = 4000.0}]",
                                    "initial.soil=[{shape = \"box\", lower = [0, 0], upper = [0.2, 0.1]}, "
                                    "{shape = \"box\", lower = [0, 0], upper = [0.2, 0.05], material = \"lower\"}]"}),
      45, true);
  std::printf("layered collapse restarted from its checkpoint at t = %.3g s\n", t);
}

// A checkpoint written before the periodic join's moment was kept (docs/method.md, "The potential
// energy along the strip") ends its numbers after the Lode bins: it is read, with the moment at 0,
// and a non-periodic run goes on exactly as before. (Before, a restart refused it: the simulation
// asked for as many numbers as it writes.)
TEST(Restart, CollapseContinuesFromACheckpointOfBeforeTheJoinsMoment) {
  const double t = expect_restart_reproduces(
      "cases/bui2008_experiment.toml",
      test::bui2008_at_courant_one(
          {"mesh.cells=[60,20]", "time.end=0.3", "output.interval=0.1", "output.progress_seconds=0"}),
      45, true, [](const std::filesystem::path& checkpoint) {
        // fields.bin: a header of the magic and seven counts (nx, ny, ghosts, fields, ranks, shared,
        // summed), the fields, then each rank's row of its shared and summed numbers.
        const auto path = checkpoint / "fields.bin";
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        std::uint64_t magic = 0;
        std::int64_t counts[7];
        f.read(reinterpret_cast<char*>(&magic), sizeof magic);
        f.read(reinterpret_cast<char*>(counts), sizeof counts);
        const std::int64_t ranks = counts[4], width = counts[5] + counts[6];
        const auto rows_at = std::streamoff(std::filesystem::file_size(path)) - std::streamoff(sizeof(double) * ranks * width);
        std::vector<double> rows(size_t(ranks * width)), kept;
        f.seekg(rows_at);
        f.read(reinterpret_cast<char*>(rows.data()), std::streamsize(rows.size() * sizeof(double)));
        for (std::int64_t r = 0; r < ranks; ++r)
          kept.insert(kept.end(), rows.begin() + r * width, rows.begin() + (r + 1) * width - 1);
        counts[6] -= 1;
        f.seekp(sizeof magic);
        f.write(reinterpret_cast<const char*>(counts), sizeof counts);
        f.seekp(rows_at);
        f.write(reinterpret_cast<const char*>(kept.data()), std::streamsize(kept.size() * sizeof(double)));
        ASSERT_TRUE(f.good());
        f.close();
        std::filesystem::resize_file(path, std::uintmax_t(rows_at) + kept.size() * sizeof(double));
        as_written_before_checksums(checkpoint);
      });
  std::printf("collapse restarted from a checkpoint without the join's moment at t = %.3g s\n", t);
}

// A checkpoint written before the energy through the sides was kept: run.txt without its boundary_work
// line and history rows without that column. It is read: its rows take the column empty (nan), so that
// each stays under its header, and the run goes on with the energy through the sides from 0, which then
// grows as the never-stopped run's does from the checkpoint on. A value that is not a number is refused.
TEST(Restart, ACheckpointOfBeforeTheEnergyThroughTheSidesGoesOnFromZero) {
  const auto whole_dir = scratch("restart_work_whole"), dir = scratch("restart_work");
  test::remove_scratch(whole_dir);
  test::remove_scratch(dir);
  const std::vector<std::string> first{"mesh.cells=[30,10]", "time.end=0.04", "output.interval=0.04",
                                       "output.progress_seconds=0", "output.fields=false"};
  auto second = first;
  second[1] = "time.end=0.08";
  double work_at_checkpoint = 0.0, work_at_end = 0.0;
  {
    Simulation whole(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(second), whole_dir);
    whole.run();
    work_at_end = whole.boundary_work();
    Simulation stopped(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(first), dir);
    stopped.run();
    work_at_checkpoint = stopped.boundary_work();
  }
  const auto run_txt = dir / "checkpoint" / "run.txt";
  std::string old_text;
  if (test::is_root()) {
    as_written_before_checksums(dir / "checkpoint");
    std::istringstream in(test::file_text(run_txt));
    std::string line;
    bool in_history = false;
    while (std::getline(in, line)) {
      if (line.rfind("boundary_work ", 0) == 0) continue;
      if (in_history && line.rfind("domain ", 0) == 0) in_history = false;
      if (in_history) {  // without its 14th field
        size_t at = 0;
        for (int k = 0; k < 13; ++k) at = line.find(',', at) + 1;
        line.erase(at, line.find(',', at) + 1 - at);
      }
      if (line.rfind("history ", 0) == 0) in_history = true;
      old_text += line + "\n";
    }
    std::ofstream(run_txt) << old_text;
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  {
    Simulation resumed(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(second), dir);
    resumed.restart();
    EXPECT_EQ(resumed.boundary_work(), 0.0);
    resumed.run();
    std::printf("energy through the sides from t = 0.04 to 0.08 s: %.12g J/m after the restart, %.12g in the run "
                "never stopped\n", resumed.boundary_work(), work_at_end - work_at_checkpoint);
    EXPECT_NE(work_at_checkpoint, 0.0);
    EXPECT_NEAR(resumed.boundary_work(), work_at_end - work_at_checkpoint, 1e-9 * std::abs(work_at_end));
  }
  if (test::is_root()) {
    const auto h = test::read_csv((dir / "history.csv").string());
    const auto &t = h.at("time"), &work = h.at("boundary_work"), &speed = h.at("soil_speed");
    ASSERT_GT(t.size(), 2u);
    EXPECT_TRUE(std::isnan(work.front()));
    EXPECT_TRUE(std::isfinite(speed.front()));  // the columns after it stay under their headers
    EXPECT_TRUE(std::isfinite(h.at("force_north_y").front()));
    EXPECT_TRUE(std::isfinite(work.back()));
    std::string text = old_text + "boundary_work abc\n";
    std::ofstream(run_txt) << text;
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  Simulation damaged(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(second), dir);
  const std::string refused = refusal(damaged);
  EXPECT_NE(refused.find("'abc' is not the energy brought in through the sides"), std::string::npos) << refused;
  test::remove_scratch(whole_dir);
  test::remove_scratch(dir);
}

TEST(Restart, CavityContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/lid_driven_cavity_re100.toml",
      {"mesh.cells=[24,24]", "time.end=1.0", "time.max_dt=0.02", "time.steady_tolerance=0", "output.interval=0.25",
       "output.progress_seconds=0"},
      30, false);
  std::printf("cavity restarted from its checkpoint at t = %.3g s\n", t);
}

// A periodic strip: the checkpoint's fields go back into vectors whose ghosts wrap along x (PETSc's
// local-to-global insertion refuses a periodic axis that one rank holds whole).
TEST(Restart, PeriodicChuteContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/bagnold_chute.toml",
      {"time.end=1.2", "output.interval=0.5", "output.fields=false", "output.progress_seconds=0"}, 150, true);
  std::printf("periodic chute restarted from its checkpoint at t = %.3g s\n", t);
}

// A chute fed through an inlet (1 mm cells), stopped while its front still runs: the inlet's ghosts
// and faces are the case's again after the checkpoint is read.
TEST(Restart, AChuteFedThroughAnInletContinuesExactlyFromItsLastCheckpoint) {
  const double t = expect_restart_reproduces(
      "cases/chute_inlet.toml",
      {"mesh.cells=[100,15]", "time.end=0.2", "output.interval=0.1", "output.fields=false",
       "output.progress_seconds=0"},
      120, true);
  std::printf("fed chute restarted from its checkpoint at t = %.3g s\n", t);
  // The same fed on a ramp, its factor in the middle of the step after the checkpoint's.
  const double ramped = expect_restart_reproduces(
      "cases/chute_inlet.toml",
      {"mesh.cells=[100,15]", "time.end=0.2", "output.interval=0.1", "output.fields=false", "output.progress_seconds=0",
       "boundary.west={type = \"inlet\", velocity = [0.3708, 0.0], soil_fraction = 1.0, soil_depth = 0.005, "
       "schedule = [[0.0, 0.5], [0.3, 1.0]]}"},
      120, true);
  std::printf("chute fed on a ramp restarted from its checkpoint at t = %.3g s\n", ramped);
}

// Preconditioners kept over several solves (solver.*.reuse_preconditioner) are rebuilt where a
// checkpoint is written, as a restarted run builds its own there.
TEST(Restart, DamBreakWithReusedPreconditionersContinuesExactly) {
  const double t = expect_restart_reproduces(
      "cases/water_dam_break.toml",
      {"mesh.cells=[49,21]", "time.end=0.15", "output.interval=0.05", "output.fields=false",
       "solver.pressure.reuse_preconditioner=10", "solver.momentum.reuse_preconditioner=10",
       "output.progress_seconds=0"},
      40, true);
  std::printf("dam break restarted from its checkpoint at t = %.3g s\n", t);
}

// time.max_steps counts the steps of the whole run, over restarts; a run stopped by it writes its
// output and a checkpoint where it stopped, once, also when that is an output time.
TEST(Restart, MaxStepsCountsTheWholeRunAndItsLastOutputOnce) {
  const auto whole_dir = scratch("max_steps_whole"), split_dir = scratch("max_steps_split");
  test::remove_scratch(whole_dir);
  test::remove_scratch(split_dir);
  auto overrides = std::vector<std::string>{"mesh.cells=[16,16]", "time.end=10", "time.dt=0.01", "time.adaptive=false",
                                            "time.steady_tolerance=0", "output.interval=0.1", "output.progress_seconds=0"};
  auto with_steps = [&](long n) {
    auto o = overrides;
    o.push_back("time.max_steps=" + std::to_string(n));
    return load_case(test::repo_path("cases/lid_driven_cavity_re100.toml"), o);
  };
  double whole_time = 0.0;
  {
    Simulation sim(PETSC_COMM_WORLD, with_steps(50), whole_dir);  // ends on the output time 0.5
    EXPECT_EQ(sim.run().steps, 50);
    whole_time = sim.time();
  }
  {
    Simulation sim(PETSC_COMM_WORLD, with_steps(25), split_dir);
    EXPECT_EQ(sim.run().steps, 25);
  }
  {
    Simulation sim(PETSC_COMM_WORLD, with_steps(50), split_dir);
    sim.restart();
    EXPECT_NEAR(sim.time(), 0.25, 1e-12);  // where the first part stopped, between outputs
    EXPECT_EQ(sim.run().steps, 25);         // the rest of 50
    EXPECT_EQ(sim.time(), whole_time);
  }
  const std::string split_pvd = test::is_root() ? test::file_text(split_dir / "fields.pvd") : "";
  {
    // Nothing left to do: refused, as a restart whose time.end is not past the checkpoint's, and
    // nothing written.
    Simulation sim(PETSC_COMM_WORLD, with_steps(50), split_dir);
    EXPECT_THROW(sim.restart(), CheckpointError);
  }
  if (test::is_root()) EXPECT_EQ(test::file_text(split_dir / "fields.pvd"), split_pvd);
  if (test::is_root()) {
    const std::string pvd = test::file_text(whole_dir / "fields.pvd");
    EXPECT_EQ(pvd.find("timestep=\"0.5\""), pvd.rfind("timestep=\"0.5\"")) << pvd;  // written once
    EXPECT_NE(pvd.find("timestep=\"0.5\""), std::string::npos) << pvd;
  }
  test::remove_scratch(whole_dir);
  test::remove_scratch(split_dir);
}

// What a restart that must be refused says.
std::string refusal(Simulation& sim) {
  try {
    sim.restart();
  } catch (const CheckpointError& e) {
    return e.what();
  }
  ADD_FAILURE() << "a foreign checkpoint was taken";
  return {};
}

// A checkpoint of a mesh of layers is refused by a case of another depth in cells, and by a planar
// case, each naming both meshes.
TEST(Restart, RefusesACheckpointOfLayersOfAnotherMesh) {
  const auto dir = scratch("restart_layers_foreign");
  std::filesystem::remove_all(dir);
  const std::vector<std::string> small{"mesh.cells=[10,4,10]", "mesh.upper=[0.4,0.16,0.4]", "time.end=0.01",
                                       "output.times=[0.005]", "output.progress_seconds=0", "output.fields=false"};
  {
    Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path("cases/lube2004_a05_3d.toml"), small), dir);
    sim.run();
  }
  auto refusal_of = [&](const std::string& case_file, const std::vector<std::string>& overrides) {
    Simulation sim(PETSC_COMM_WORLD, load_case(test::repo_path(case_file), overrides), dir);
    return refusal(sim);
  };
  auto deeper = small;
  deeper[0] = "mesh.cells=[10,4,8]";
  const std::string layers = refusal_of("cases/lube2004_a05_3d.toml", deeper);
  EXPECT_NE(layers.find("the checkpoint is of a 10 x 4 x 10 mesh, the case has 10 x 4 x 8 cells"), std::string::npos)
      << layers;
  const std::string planar = refusal_of("cases/lube2004_a05.toml", {"mesh.cells=[10,4]", "time.end=0.1"});
  EXPECT_NE(planar.find("the checkpoint is of a 10 x 4 x 10 mesh, the case has 10 x 4 cells"), std::string::npos)
      << planar;
  test::remove_scratch(dir);
}

TEST(Restart, RefusesAMissingOrForeignCheckpoint) {
  const auto dir = scratch("restart_foreign");
  std::filesystem::remove_all(dir);
  const std::vector<std::string> small{"mesh.cells=[30,10]", "time.end=0.05", "output.interval=0.05",
                                       "output.progress_seconds=0", "output.fields=false"};
  {
    Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), dir);
    EXPECT_THROW(sim.restart(), CheckpointError);  // nothing written yet
    sim.run();
  }
  auto other = small;
  other[0] = "mesh.cells=[32,10]";
  Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(other), dir);
  const std::string mesh = refusal(sim);
  EXPECT_NE(mesh.find("30 x 10"), std::string::npos) << mesh;
  // With obstacles another mesh blocks other cells too, so the domains differ: the mesh is named,
  // the cause, not the count of blocked cells.
  {
    const auto barrier = scratch("restart_foreign_barrier");
    std::filesystem::remove_all(barrier);
    auto on = [&](const char* cells) {
      auto keys = small;
      keys[0] = cells;
      return load_case(test::repo_path("cases/barrier_collapse.toml"), keys);
    };
    Simulation(PETSC_COMM_WORLD, on("mesh.cells=[150,50]"), barrier).run();
    Simulation finer(PETSC_COMM_WORLD, on("mesh.cells=[160,50]"), barrier);
    const std::string finer_mesh = refusal(finer);
    EXPECT_NE(finer_mesh.find("the checkpoint is of a 150 x 50 mesh, the case has 160 x 50 cells"), std::string::npos)
        << finer_mesh;
    std::filesystem::remove_all(barrier);
  }
  // Other numerics keep other fields; where the count alone would agree (the projection with the
  // look-ahead keeps the last step's velocity where the coupled solve keeps cell forces), the
  // names tell them apart.
  auto numerics = small;
  numerics.push_back("numerics.first_viscosity=previous_step");
  Simulation other_numerics(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(numerics), dir);
  const std::string fields = refusal(other_numerics);
  EXPECT_NE(fields.find("the checkpoint holds the fields of other numerics (u v face_u"), std::string::npos) << fields;
  EXPECT_NE(fields.find("u_previous v_previous solve_region carried_density c displacement_x displacement_y); this case's "
                        "are u v"),
            std::string::npos) << fields;
  // The mass a cell's momentum was carried with is kept only where the step reads it: a checkpoint of a
  // run that kept the velocity at the density's jumps (and those written before) is told apart, and
  // the other way round, each with the setting to restart it with.
  auto velocity_kept = small;
  velocity_kept.push_back("numerics.density_jump=keep_velocity");
  Simulation kept(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(velocity_kept), dir);
  const std::string to_kept = refusal(kept);
  EXPECT_NE(to_kept.find("kept the kinetic energy a cell's momentum was carried with (numerics.density_jump = "
                         "\"keep_kinetic_energy\"); restart it with that"), std::string::npos) << to_kept;
  {
    const auto older = scratch("restart_velocity_kept");
    std::filesystem::remove_all(older);
    Simulation(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(velocity_kept), older).run();
    Simulation now(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), older);
    const std::string from_kept = refusal(now);
    EXPECT_NE(from_kept.find("restart it with --set numerics.density_jump=keep_velocity"), std::string::npos) << from_kept;
    auto longer = velocity_kept;  // ... and restarts with the setting it was written with
    longer[1] = "time.end=0.1";
    Simulation again(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(longer), older);
    EXPECT_NO_THROW(again.restart());
    std::filesystem::remove_all(older);
  }
  // A cut fields file, and one of the format before it (a file per rank), are named as such.
  {
    const auto checkpoint = dir / "checkpoint", fields_bin = checkpoint / "fields.bin", kept = dir / "fields.bin.kept";
    std::filesystem::copy_file(fields_bin, kept);
    std::filesystem::resize_file(fields_bin, std::filesystem::file_size(fields_bin) - 8);
    Simulation cut(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), dir);
    const std::string truncated = refusal(cut);
    EXPECT_NE(truncated.find("fields.bin is truncated or damaged"), std::string::npos) << truncated;
    std::filesystem::rename(fields_bin, checkpoint / "rank_0.bin");
    Simulation older(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), dir);
    const std::string format_2 = refusal(older);
    EXPECT_NE(format_2.find("written by an earlier version of granflow (checkpoint format 2"), std::string::npos)
        << format_2;
    std::filesystem::remove(checkpoint / "rank_0.bin");
    std::filesystem::rename(kept, fields_bin);
  }
  // Values no run writes (NaN in a velocity, a soil fraction of 2) are damage done to the file after
  // it was written: named, with the field and the cell, before the run goes on from them. Where the
  // checkpoint has its checksums, any change of a value is refused (the next block); these are the
  // checks that remain for a checkpoint written before them.
  const auto run_txt = dir / "checkpoint" / "run.txt";
  as_written_before_checksums(dir / "checkpoint");
  {
    const auto fields_bin = dir / "checkpoint" / "fields.bin", kept = dir / "fields.bin.kept";
    std::filesystem::copy_file(fields_bin, kept);
    // The field named `name` at cell (i, j), as the header lays the fields out (checkpoint.cpp).
    std::int64_t header[8];
    std::ifstream(fields_bin, std::ios::binary).read(reinterpret_cast<char*>(header), sizeof header);
    const std::int64_t nx = header[1], ny = header[2], ghosts = header[3];
    const std::string run_txt = test::file_text(dir / "checkpoint" / "run.txt");
    const size_t names_at = run_txt.find("\nfields ") + 8;
    std::istringstream names(run_txt.substr(names_at, run_txt.find('\n', names_at) - names_at));
    std::vector<std::string> order{std::istream_iterator<std::string>(names), std::istream_iterator<std::string>()};
    auto poke = [&](const std::string& name, int i, int j, double value) {
      const auto k = std::find(order.begin(), order.end(), name) - order.begin();
      ASSERT_LT(size_t(k), order.size()) << name;
      const std::int64_t at = std::int64_t(sizeof header) +
                              8 * ((k * (ny + 2 * ghosts) + j + ghosts) * (nx + 2 * ghosts) + i + ghosts);
      std::fstream file(fields_bin, std::ios::binary | std::ios::in | std::ios::out);
      file.seekp(at);
      file.write(reinterpret_cast<const char*>(&value), sizeof value);
    };
    poke("u", 7, 3, std::nan(""));
    Simulation nan_u(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), dir);
    const std::string not_finite = refusal(nan_u);
    EXPECT_NE(not_finite.find("the checkpoint is damaged: its field u holds nan in cell (7, 3)"), std::string::npos)
        << not_finite;
    std::filesystem::copy_file(kept, fields_bin, std::filesystem::copy_options::overwrite_existing);
    poke("c", 2, 1, 2.0);
    Simulation two(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), dir);
    const std::string outside = refusal(two);
    EXPECT_NE(outside.find("the checkpoint is damaged: its soil fraction c is 2 in cell (2, 1), outside [0, 1]"),
              std::string::npos)
        << outside;
    // Round-off beyond [0, 1] is what the sweeps leave, and is taken.
    poke("c", 2, 1, 1 + 1e-13);
    auto longer = small;
    longer.push_back("time.end=0.1");
    Simulation round_off(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(longer), dir);
    EXPECT_NO_THROW(round_off.restart());
    std::filesystem::rename(kept, fields_bin);
  }
  // A run of more steps than an int holds restarts (time.max_steps goes to 1e12).
  {
    std::string text = test::file_text(run_txt);
    const size_t at = text.find("\nsteps ");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, text.find('\n', at + 1) - at, "\nsteps 3000000000");
    std::ofstream(run_txt) << text;
    auto longer = small;
    longer.insert(longer.end(), {"time.end=0.1", "time.max_steps=1000000000000"});
    Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(longer), dir);
    EXPECT_NO_THROW(sim.restart());
    text.replace(text.find("\nsteps "), std::string("\nsteps 3000000000").size(), "\nsteps 99999999999999999999");
    std::ofstream(run_txt) << text;
    Simulation damaged(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(longer), dir);
    EXPECT_THROW(damaged.restart(), CheckpointError);
  }
  std::filesystem::remove_all(dir);
}

// With its checksums a checkpoint altered after it was written is refused, though every value is one
// a run could hold: a velocity nudged by 1e-12 m/s, run.txt's dissipated energy changed, or
// fields.bin taken from another checkpoint of the same case and mesh; and run.txt cut short in its
// checksum line. Put back, it is taken.
TEST(Restart, RefusesACheckpointThatDoesNotMatchItsChecksums) {
  const auto dir = scratch("restart_checksum"), other = scratch("restart_checksum_other");
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(other);
  const std::vector<std::string> small{"mesh.cells=[30,10]", "time.end=0.05", "output.interval=0.05",
                                       "output.progress_seconds=0", "output.fields=false"};
  auto earlier = small;
  earlier[1] = "time.end=0.04";
  earlier[2] = "output.interval=0.04";
  Simulation(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(small), dir).run();
  Simulation(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(earlier), other).run();
  auto longer = small;
  longer.push_back("time.end=0.1");
  auto restart_says = [&]() -> std::string {
    Simulation sim(PETSC_COMM_WORLD, test::bui2008_case_at_courant_one(longer), dir);
    try {
      sim.restart();
    } catch (const CheckpointError& e) {
      return e.what();
    }
    return "taken";
  };
  const auto checkpoint = dir / "checkpoint", fields_bin = checkpoint / "fields.bin", run_txt = checkpoint / "run.txt";
  const std::string fields_text = test::file_text(fields_bin), run_text = test::file_text(run_txt);
  auto put_back = [&] {
    std::ofstream(fields_bin, std::ios::binary) << fields_text;
    std::ofstream(run_txt, std::ios::binary) << run_text;
  };
  const std::string refused_fields = "does not match the checksum in run.txt (altered after it was written, or of "
                                     "another checkpoint)";
  {
    // The first value of the fields after the header's eight words: a ghost of u, nudged.
    std::fstream file(fields_bin, std::ios::binary | std::ios::in | std::ios::out);
    double u = 0.0;
    file.seekg(64);
    file.read(reinterpret_cast<char*>(&u), sizeof u);
    u += 1e-12;
    file.seekp(64);
    file.write(reinterpret_cast<const char*>(&u), sizeof u);
  }
  const std::string nudged = restart_says();
  EXPECT_NE(nudged.find("fields.bin " + refused_fields), std::string::npos) << nudged;
  put_back();
  {
    std::string text = run_text;
    const size_t at = text.find("\ndissipated_energy ");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, text.find('\n', at + 1) - at, "\ndissipated_energy 0x1p-10");
    std::ofstream(run_txt, std::ios::binary) << text;
  }
  const std::string energy = restart_says();
  EXPECT_NE(energy.find("the checkpoint is damaged: " + run_txt.string() + " does not match its checksum"),
            std::string::npos) << energy;
  put_back();
  std::filesystem::copy_file(other / "checkpoint" / "fields.bin", fields_bin,
                             std::filesystem::copy_options::overwrite_existing);
  const std::string swapped = restart_says();
  EXPECT_NE(swapped.find("fields.bin " + refused_fields), std::string::npos) << swapped;
  put_back();
  // Cut short in its checksum line, run.txt must not pass for one written before the checksums.
  std::ofstream(run_txt, std::ios::binary) << run_text.substr(0, run_text.rfind("\nchecksum ") + 7);
  const std::string cut = restart_says();
  EXPECT_NE(cut.find(run_txt.string() + " is truncated"), std::string::npos) << cut;
  put_back();
  EXPECT_EQ(restart_says(), "taken");
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(other);
}

}  // namespace
}  // namespace granflow

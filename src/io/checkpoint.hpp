#pragma once
// Checkpoint of a run, written at each output time into OUT/checkpoint/: what the time loop needs to
// continue where it stopped. The fields are stored over the whole mesh, the boundary's ghost cells
// included, as raw doubles in one file (fields.bin, written and read by all ranks through MPI-IO),
// so that a restart may take another number of ranks; rank 0 adds the run's clock, the history rows
// and the field-series index as text (run.txt), ending with checksums of both files. A restart must
// use the same mesh.
#include <mpi.h>

#include <array>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mesh/field.hpp"

namespace granflow {

struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Rank 0's part: the run's clock and what it has written so far.
struct RunCheckpoint {
  double time = 0.0;
  double next_dt = 0.0;  // the step the loop would take next
  int output_index = 0;
  double dissipated_energy = 0.0;
  double initial_soil_volume = 0.0;
  std::vector<std::string> history;                      // rows of history.csv
  std::vector<std::pair<double, std::string>> series;    // entries of fields.pvd
  std::string domain;  // the domain the fields are of, as Simulation describes it ("" in older checkpoints)
  long steps = 0;      // steps taken so far (0 in older checkpoints)
  std::string physics; // the materials and gravity, as Simulation describes them ("" in older checkpoints)
  std::string fields;  // the fields' names in the order written ("" in older checkpoints)
  std::string boundaries;  // the sides' conditions, as Simulation describes them ("" in older checkpoints)
  double boundary_work = 0.0;  // the energy brought in through the sides so far (0 in older checkpoints)
};

// The numbers a checkpoint holds besides the fields: `shared` are the same on every rank (a step
// size, a sweep order); `summed` are this rank's shares of totals (soil carried out, energy by Lode
// angle), which a restart on another number of ranks gives to rank 0 whole and to the others as 0.
struct CheckpointScalars {
  std::vector<double> shared;
  std::vector<double> summed;
};

// Writes the checkpoint into dir/checkpoint/ (collective). It is assembled in checkpoint.partial/ and
// swapped in whole, so a run killed while writing keeps the previous checkpoint.
// `cells`: the mesh's nx, ny and nz (1 on a planar or axisymmetric mesh).
void write_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, const std::array<int, 3>& cells,
                      const RunCheckpoint& run, std::span<Field* const> fields, const CheckpointScalars& scalars);

// Reads the checkpoint of dir back (collective): the fields in the same order as written, each rank's
// window of them with its ghosts; the scalars into `scalars` (this rank's own where the number of
// ranks is the one written, else as CheckpointScalars says); and rank 0's run part into the return
// value (on every rank; the history, series and domain on rank 0 only). Throws CheckpointError naming
// what does not match, on every rank: the mesh, the fields (their number, and their names where the
// checkpoint records them, against `field_names`), a domain other than `domain`, or a file that does
// not match its checksum (where run.txt gives them: older checkpoints do not). Nothing is read
// into the fields unless the run's record matches.
RunCheckpoint read_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, const std::array<int, 3>& cells,
                              const std::string& domain, const std::string& field_names,
                              std::span<Field* const> fields, CheckpointScalars& scalars);

}  // namespace granflow

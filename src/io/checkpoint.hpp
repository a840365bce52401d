#pragma once
// Checkpoint of a run, written at each output time into OUT/checkpoint/: what the time loop needs to
// continue exactly where it stopped. Each rank writes its own part of the fields, ghosts
// included, as raw doubles (rank_N.bin); rank 0 adds the run's clock, the history rows and the
// field-series index as text (run.txt). A restart must use the same mesh and the same number of ranks.
#include <mpi.h>

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
};

// Writes the checkpoint into dir/checkpoint/ (collective). It is assembled in checkpoint.partial/ and
// swapped in whole, so a run killed while writing keeps the previous checkpoint.
void write_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, int nx, int ny, const RunCheckpoint& run,
                      std::span<Field* const> fields, std::span<const double> scalars);

// Reads the checkpoint of dir back (collective): the fields in the same order as written, this rank's
// scalars into `scalars` and rank 0's run part into the return value (on every rank; the history,
// series and domain on rank 0 only). Throws CheckpointError naming what does not match, on every rank:
// the number of ranks, the mesh, the fields (their number, and their names where the checkpoint
// records them, against `field_names`), or a domain other than `domain`. Nothing is read into the
// fields unless the run's record matches.
RunCheckpoint read_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, int nx, int ny,
                              const std::string& domain, const std::string& field_names,
                              std::span<Field* const> fields, std::vector<double>& scalars);

}  // namespace granflow

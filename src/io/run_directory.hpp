#pragma once
// The files a run writes into its output directory, as far as a later run there must know them: to
// refuse to run over them, or to remove them all with --overwrite (so that no file of the earlier
// run is left beside the new run's).
#include <filesystem>
#include <vector>

namespace granflow {

// The run's files in `dir`: fields.pvd, history.csv, lode_dissipation.csv, the checkpoint
// directories, every numbered file NAME_NNNNN.csv or NAME_NNNNN.vtr, and the latest copy NAME.csv
// of each numbered series. Empty if `dir` is not a directory.
std::vector<std::filesystem::path> run_files_in(const std::filesystem::path& dir);

}  // namespace granflow

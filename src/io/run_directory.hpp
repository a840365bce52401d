#pragma once
// The files a run writes into its output directory, as far as a later run there must know them: to
// refuse to run over them, or to remove them all with --overwrite (so that no file of the earlier
// run is left beside the new run's). A file of any other name is not a run's and is left alone.
//
// The run's fixed files and series are known by name; its line samples are named in the case, so
// the run records their names in the directory (run_record_name) for a later run to find them.
#include <filesystem>
#include <vector>

#include "io/case_file.hpp"

namespace granflow {

inline constexpr const char* run_record_name = "granflow_run.txt";

// The earlier run's files in `dir`: fields.pvd and fields_NNNNN.vtr, history.csv,
// lode_dissipation.csv, the numbered soil series (surface_, failure_line_, column_height_), the
// checkpoint directories, the record, and NAME.csv and NAME_NNNNN.csv of each line sample the record
// names or `lines` (the new run's) holds. Empty if `dir` is not a directory.
std::vector<std::filesystem::path> run_files_in(const std::filesystem::path& dir, const std::vector<LineSample>& lines);

// Writes the record of `lines` into `dir`, keeping the names an earlier record there holds (a restart
// with other line samples leaves both kinds of file). Throws std::runtime_error if it cannot write.
void record_run(const std::filesystem::path& dir, const std::vector<LineSample>& lines);

}  // namespace granflow

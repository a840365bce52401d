#pragma once
// The files a run writes into its output directory, as far as a later run there must know them: to
// refuse to run over them, or to remove them all with --overwrite (so that no file of the earlier
// run is left beside the new run's). A file of any other name is not a run's and is left alone.
//
// The run's fixed files and series are known by name; its line samples are named in the case, so
// the run records their names in the directory (run_record_name) for a later run to find them.
#include <filesystem>
#include <string>
#include <vector>

#include "io/case_file.hpp"

namespace granflow {

inline constexpr const char* run_record_name = "granflow_run.txt";

// Where a run writes without -o: out/NAME, NAME the case file's name without its extension, followed
// by `suffix`. A name that would point back into out/ or above it ("..toml", "...toml") is refused
// (CaseError), as -o must then say where.
std::filesystem::path default_output_directory(const std::filesystem::path& case_file, const std::string& suffix);
// The case as the run took it (CaseConfig::as_run), with how it was run in comment lines.
inline constexpr const char* case_record_name = "granflow_case.toml";

// The earlier run's files in `dir`: fields.pvd and fields_NNNNN.vtr, history.csv,
// lode_dissipation.csv, the numbered soil series (surface_, failure_line_, column_height_), the
// checkpoint directories, the records, and NAME.csv and NAME_NNNNN.csv of each line sample the record
// names or `lines` (the new run's) holds. Empty if `dir` is not a directory.
std::vector<std::filesystem::path> run_files_in(const std::filesystem::path& dir, const std::vector<LineSample>& lines);

// A stability analysis (granflow stability) in `dir`: its table, stability_table_name, and its trials'
// directories, F_<factor> holding any of a run's files. Empty if there is none, or `dir` is not a
// directory. A run and an analysis do not share a directory: each refuses one that holds the other's.
inline constexpr const char* stability_table_name = "stability.csv";
std::vector<std::filesystem::path> analysis_files_in(const std::filesystem::path& dir);
// The analysis `dir` is a trial directory of (its parent, when analysis_files_in lists `dir` there), or
// empty: a run there would replace the trial a continued analysis reads.
std::filesystem::path analysis_of_trial(const std::filesystem::path& dir);

// Refuses an output directory `dir` (as -o gives it) that is or lies in a directory an earlier run
// keeps to itself and replaces or removes whole: its checkpoint/, checkpoint.old/ or
// checkpoint.partial/, or a set-aside run. Output there would be lost at that run's next output.
// Returns the message naming both, or "".
std::string inside_a_runs_own_directory(const std::filesystem::path& dir);

// Removes the half-written files (.NAME.tmpPID, io/atomic_file.cpp) a killed run left in `dir`: a
// restart, which holds the directory alone (io/run_lock.hpp), writes those files anew.
void remove_left_over_files(const std::filesystem::path& dir, const std::vector<LineSample>& lines);

// --overwrite sets the earlier run aside until the new run has taken its first step, so that a new run
// that fails at once (an option its solver cannot use, a value that makes the first step diverge) does
// not cost the earlier run. The files go into dir/.replaced_run. One left there (the new run was killed
// before its first step) is the only copy of that run: a later run into `dir` is refused until the
// user moves it back or removes it (set_aside_run_in).
inline constexpr const char* set_aside_name = ".replaced_run";
// The set-aside directory a killed run left in `dir`, or empty.
std::filesystem::path set_aside_run_in(const std::filesystem::path& dir);
// Moves `files` (the earlier run's, in `dir`) aside. Returns a message naming what failed, or "",
// having moved back what it had moved.
std::string set_aside_run(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& files);
// The new run is under way: removes the set-aside files.
void discard_set_aside_run(const std::filesystem::path& dir);
// The new run failed before its first step: removes its files (those of `lines` and the record's) and
// moves the set-aside files back. Whatever cannot come back stays in the set-aside, which is then kept.
void restore_set_aside_run(const std::filesystem::path& dir, const std::vector<LineSample>& lines);

// Writes the record of `lines` into `dir`, keeping the names an earlier record there holds (a restart
// with other line samples leaves both kinds of file). Throws std::runtime_error if it cannot write.
void record_run(const std::filesystem::path& dir, const std::vector<LineSample>& lines);

// Writes the case as the run took it into `dir` (case_record_name): how it was run (the case file, the
// --set assignments, the version and the number of ranks, the checkpoint's time if it was continued
// from one) in comment lines, then the case with the assignments applied, which `granflow run` takes
// as it is. Throws std::runtime_error if it cannot write.
void record_case(const std::filesystem::path& dir, const CaseConfig& config, int ranks, double continued_from = -1.0);

}  // namespace granflow

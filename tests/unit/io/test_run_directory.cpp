// The files of an earlier run in an output directory: the run's own series and the line samples it
// recorded or the new run names, never a file of another name.
#include "io/run_directory.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <initializer_list>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace granflow {
namespace {

namespace fs = std::filesystem;

std::vector<LineSample> lines(std::initializer_list<const char*> names) {
  std::vector<LineSample> out;
  for (const char* n : names) out.push_back({n});
  return out;
}

std::vector<std::string> names_of(const std::vector<fs::path>& files) {
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(f.filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RunDirectory, FindsTheRunsFilesAndLeavesOthers) {
  const fs::path dir = fs::temp_directory_path() / ("granflow_run_directory_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "checkpoint");
  for (const char* name : {"fields.pvd", "fields_00000.vtr", "history.csv", "lode_dissipation.csv", "surface_00003.csv",
                           "failure_line_00003.csv", "column_height_00003.csv", "old_line.csv", "old_line_00002.csv",
                           "new_line_00000.csv", "survey.csv", "survey_20240.csv", "notes.txt", "fields_1.vtr",
                           "granflow_case.toml", "case.toml"})
    std::ofstream(dir / name) << "x\n";
  EXPECT_EQ(names_of(run_files_in(dir, {})),
            (std::vector<std::string>{"checkpoint", "column_height_00003.csv", "failure_line_00003.csv", "fields.pvd",
                                      "fields_00000.vtr", "granflow_case.toml", "history.csv", "lode_dissipation.csv",
                                      "surface_00003.csv"}));
  record_run(dir, lines({"old_line"}));
  const auto with_lines = names_of(run_files_in(dir, lines({"new_line"})));
  for (const char* name : {"old_line.csv", "old_line_00002.csv", "new_line_00000.csv", run_record_name})
    EXPECT_TRUE(std::count(with_lines.begin(), with_lines.end(), name)) << name;
  for (const char* name : {"survey.csv", "survey_20240.csv", "notes.txt", "fields_1.vtr"})
    EXPECT_FALSE(std::count(with_lines.begin(), with_lines.end(), name)) << name;
  record_run(dir, lines({"new_line"}));  // keeps the earlier record's names
  const auto both = names_of(run_files_in(dir, {}));
  EXPECT_TRUE(std::count(both.begin(), both.end(), "old_line.csv"));
  EXPECT_TRUE(std::count(both.begin(), both.end(), "new_line_00000.csv"));
  EXPECT_TRUE(run_files_in(dir / "notes.txt", {}).empty());  // not a directory
  // A record edited by hand to hold an empty name does not make every file the run's.
  std::ofstream(dir / run_record_name) << "line \n";
  const auto edited = names_of(run_files_in(dir, {}));
  EXPECT_FALSE(std::count(edited.begin(), edited.end(), "notes.txt"));
  EXPECT_FALSE(std::count(edited.begin(), edited.end(), "survey.csv"));
  fs::remove_all(dir);
}

// A run killed while it wrote a file leaves .NAME.tmpPID (io/atomic_file.cpp): the run's, if NAME is.
TEST(RunDirectory, FilesLeftHalfWrittenAreTheRuns) {
  const fs::path dir = fs::temp_directory_path() / ("granflow_run_left_over_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {".fields_00001.vtr.tmp4242", ".history.csv.tmp17", ".survey.csv.tmp17", ".history.csv.tmp",
                           ".history.csv.tmpx1", ".tmp12"})
    std::ofstream(dir / name) << "x\n";
  EXPECT_EQ(names_of(run_files_in(dir, {})), (std::vector<std::string>{".fields_00001.vtr.tmp4242", ".history.csv.tmp17"}));
  // A restart removes them, and only them; the run's finished files stay.
  std::ofstream(dir / "history.csv") << "x\n";
  remove_left_over_files(dir, {});
  EXPECT_EQ(names_of(run_files_in(dir, {})), (std::vector<std::string>{"history.csv"}));
  EXPECT_TRUE(fs::exists(dir / ".survey.csv.tmp17"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granflow

#include "io/run_directory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <system_error>

#include "io/atomic_file.hpp"
#include "io/case_error.hpp"
#include "io/utf8_text.hpp"

namespace granflow {

std::filesystem::path default_output_directory(const std::filesystem::path& case_file, const std::string& suffix) {
  const std::string name = case_file.stem().string() + suffix;
  if (name.empty() || name == "." || name == "..")
    throw CaseError(fmt::format("{}: the case file's name gives no directory under out/ to write into; name one "
                                "with -o", case_file.string()));
  return std::filesystem::path("out") / name;
}

namespace {
// NAME_NNNNN.EXT with five or more digits: the stem NAME, or "" if `name` is not of that form.
std::string numbered_stem(const std::string& name, const std::string& extension) {
  if (name.size() <= extension.size() || name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
    return {};
  const std::string base = name.substr(0, name.size() - extension.size());
  const size_t underscore = base.find_last_of('_');
  if (underscore == std::string::npos || base.size() - underscore <= 5) return {};
  if (!std::all_of(base.begin() + long(underscore) + 1, base.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return {};
  return base.substr(0, underscore);
}

std::set<std::string> recorded_lines(const std::filesystem::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / run_record_name);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("line ", 0) == 0 && line.size() > 5) names.insert(line.substr(5));
  return names;
}
}  // namespace

std::vector<std::filesystem::path> run_files_in(const std::filesystem::path& dir, const std::vector<LineSample>& lines) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  std::set<std::string> line_names = recorded_lines(dir);
  for (const auto& line : lines) line_names.insert(line.name);
  const std::set<std::string> csv_series{"surface", "failure_line", "column_height"};
  auto is_run_file = [&](const std::string& name) {
    const bool fixed = name == "fields.pvd" || name == "history.csv" || name == "lode_dissipation.csv" ||
                       name == "checkpoint" || name == "checkpoint.old" || name == "checkpoint.partial" ||
                       name == run_record_name || name == case_record_name;
    const std::string csv_stem = numbered_stem(name, ".csv");
    const bool series = (!csv_stem.empty() && (csv_series.count(csv_stem) || line_names.count(csv_stem))) ||
                        numbered_stem(name, ".vtr") == "fields";
    const bool latest_line = name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0 &&
                             line_names.count(name.substr(0, name.size() - 4));
    return fixed || series || latest_line;
  };
  // .NAME.tmpPID: a file being written (io/atomic_file.cpp) when its run was killed.
  auto is_left_over = [&](const std::string& name) {
    const size_t tmp = name.rfind(".tmp");
    if (name.size() < 2 || name[0] != '.' || tmp == std::string::npos || tmp + 4 == name.size()) return false;
    if (!std::all_of(name.begin() + long(tmp) + 4, name.end(), [](char c) { return c >= '0' && c <= '9'; })) return false;
    return is_run_file(name.substr(1, tmp - 1));
  };
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (is_run_file(name) || is_left_over(name)) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string inside_a_runs_own_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::path path = std::filesystem::weakly_canonical(std::filesystem::absolute(dir, ec), ec);
  if (ec) return {};  // a path the system cannot resolve is refused where the directory is made
  for (; path.has_relative_path(); path = path.parent_path()) {
    const std::string name = path.filename().string();
    const bool checkpoint = name == "checkpoint" || name == "checkpoint.old" || name == "checkpoint.partial";
    if (!checkpoint && name != set_aside_name) continue;
    // A checkpoint is a run's if the run's record is beside it or its clock is inside.
    if (!checkpoint || std::filesystem::exists(path.parent_path() / run_record_name, ec) ||
        std::filesystem::exists(path / "run.txt", ec))
      return fmt::format("-o {}: inside {}, which the run in {} replaces whole; choose another directory", dir.string(),
                         path.string(), path.parent_path().string());
  }
  return {};
}

void remove_left_over_files(const std::filesystem::path& dir, const std::vector<LineSample>& lines) {
  for (const auto& f : run_files_in(dir, lines))
    if (f.filename().string().starts_with(".")) {  // the run's own files do not start with a dot
      std::error_code ignored;
      std::filesystem::remove(f, ignored);
    }
}

std::filesystem::path set_aside_run_in(const std::filesystem::path& dir) {
  std::error_code ec;
  const auto aside = dir / set_aside_name;
  return std::filesystem::exists(aside, ec) ? aside : std::filesystem::path();
}

namespace {
// Moves every entry of `aside` back into `dir`; removes `aside` only if all came back.
void move_back(const std::filesystem::path& dir, const std::filesystem::path& aside) {
  namespace fs = std::filesystem;
  std::error_code ec;
  bool all = true;
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(aside, ec)) entries.push_back(entry.path());
  for (const auto& entry : entries) {
    std::error_code moved;
    fs::rename(entry, dir / entry.filename(), moved);
    all = all && !moved;
  }
  if (all && !ec) fs::remove(aside, ec);
}
}  // namespace

std::string set_aside_run(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& files) {
  namespace fs = std::filesystem;
  const fs::path aside = dir / set_aside_name;
  std::error_code ec;
  fs::create_directory(aside, ec);
  if (ec) return "--overwrite: cannot set the earlier run aside in " + aside.string() + ": " + ec.message();
  for (const auto& file : files) {
    fs::rename(file, aside / file.filename(), ec);
    if (ec) {
      const std::string problem = "--overwrite: cannot move " + file.string() + " aside: " + ec.message();
      move_back(dir, aside);
      return problem;
    }
  }
  return {};
}

void discard_set_aside_run(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::remove_all(dir / set_aside_name, ec);  // what cannot go stays, and a later run says so
}

void restore_set_aside_run(const std::filesystem::path& dir, const std::vector<LineSample>& lines) {
  namespace fs = std::filesystem;
  const fs::path aside = dir / set_aside_name;
  std::error_code ec;
  if (!fs::is_directory(aside, ec)) return;
  for (const auto& file : run_files_in(dir, lines)) fs::remove_all(file, ec);
  move_back(dir, aside);
}

namespace {
// Text for one comment line: a line break in it (a --set value over two lines) as \n, and bytes that
// are not UTF-8 (a path's) as \xNN, since the whole file must be UTF-8 to be read again.
std::string one_line(const std::string& text) {
  std::string out;
  for (char ch : utf8_or_escaped(text)) out += ch == '\n' ? std::string("\\n") : ch == '\r' ? std::string("\\r") : std::string(1, ch);
  return out;
}
}  // namespace

void record_case(const std::filesystem::path& dir, const CaseConfig& config, int ranks, double continued_from) {
  std::string how = fmt::format("# The case as granflow {} ran it into this directory, on {} rank{}: {}\n", GRANFLOW_VERSION, ranks,
                                ranks == 1 ? "" : "s", one_line(config.source.string()));
  for (const auto& o : config.overrides) how += fmt::format("#   --set '{}'\n", one_line(o));
  if (continued_from >= 0.0) how += fmt::format("# continued from the checkpoint at t = {:.9g} s\n", continued_from);
  how += "# `granflow run` on this file runs it again (the file's comments are not kept).\n\n";
  write_file_atomically(dir / case_record_name, [&](std::ostream& out) { out << how << config.as_run << "\n"; });
}

void record_run(const std::filesystem::path& dir, const std::vector<LineSample>& lines) {
  std::set<std::string> names = recorded_lines(dir);
  for (const auto& line : lines) names.insert(line.name);
  write_file_atomically(dir / run_record_name, [&](std::ostream& out) {
    out << "# A granflow run's output directory; its line samples (a later run's --overwrite removes their files)\n";
    for (const auto& n : names) out << "line " << n << "\n";
  });
}

std::vector<std::filesystem::path> analysis_files_in(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == stability_table_name || (name.starts_with("F_") && !run_files_in(entry.path(), {}).empty()))
      found.push_back(entry.path());
  }
  return found;
}

std::filesystem::path analysis_of_trial(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  fs::path trial = dir.lexically_normal();
  if (trial.filename().empty()) trial = trial.parent_path();  // "OUT/F_1/"
  if (!trial.filename().string().starts_with("F_")) return {};
  const fs::path analysis = trial.has_parent_path() ? trial.parent_path() : fs::path(".");
  for (const auto& p : analysis_files_in(analysis))
    if (p.filename() == trial.filename()) return analysis;
  return {};
}

}  // namespace granflow

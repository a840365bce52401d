#include "io/run_directory.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <system_error>

namespace granflow {

namespace {
// NAME_NNNNN.EXT with five digits: the stem NAME, or "" if `name` is not of that form.
std::string numbered_stem(const std::string& name, const std::string& extension) {
  const size_t digits = 5, tail = 1 + digits + extension.size();  // _NNNNN.ext
  if (name.size() <= tail || name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
    return {};
  const size_t underscore = name.size() - tail;
  if (name[underscore] != '_') return {};
  for (size_t k = underscore + 1; k < underscore + 1 + digits; ++k)
    if (name[k] < '0' || name[k] > '9') return {};
  return name.substr(0, underscore);
}
}  // namespace

std::vector<std::filesystem::path> run_files_in(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  std::set<std::string> series;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == "fields.pvd" || name == "history.csv" || name == "lode_dissipation.csv" || name == "checkpoint" ||
        name == "checkpoint.old" || name == "checkpoint.partial") {
      files.push_back(entry.path());
    } else if (auto stem = numbered_stem(name, ".csv"); !stem.empty()) {
      files.push_back(entry.path());
      series.insert(stem);
    } else if (!numbered_stem(name, ".vtr").empty()) {
      files.push_back(entry.path());
    }
  }
  for (const auto& stem : series)
    if (fs::exists(dir / (stem + ".csv"), ec)) files.push_back(dir / (stem + ".csv"));
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace granflow

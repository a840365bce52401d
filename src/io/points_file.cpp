#include "io/points_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string_view>

#include "io/case_error.hpp"

namespace granflow {

namespace {

// The numbers of a line, fields separated by commas and blanks; false where a field is not a number.
bool parse_numbers(std::string_view line, std::vector<double>& out) {
  out.clear();
  size_t k = 0;
  auto separator = [](char ch) { return ch == ',' || ch == ' ' || ch == '\t' || ch == '\r' || ch == ';'; };
  while (k < line.size()) {
    while (k < line.size() && separator(line[k])) ++k;
    if (k == line.size()) break;
    size_t end = k;
    while (end < line.size() && !separator(line[end])) ++end;
    const std::string_view field = line.substr(k, end - k);
    double value = 0.0;
    const char* first = field.data() + (field.front() == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), value);
    if (ec != std::errc() || ptr != field.data() + field.size()) return false;
    out.push_back(value);
    k = end;
  }
  return true;
}

}  // namespace

std::vector<std::array<double, 2>> read_points_file(const std::filesystem::path& file, const std::string& key_path) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw CaseError(fmt::format("{}: '{}' is a directory, not a file of points", key_path, file.string()));
  std::ifstream in(file);
  if (!in) throw CaseError(fmt::format("{}: cannot open '{}': {}", key_path, file.string(), std::strerror(errno)));
  std::vector<std::array<double, 2>> points;
  std::vector<double> numbers;
  bool first = true;
  long number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    const bool parsed = parse_numbers(line, numbers);
    const bool header = first && !parsed;
    first = false;
    if (header) continue;
    if (!parsed || numbers.size() != 2 || !std::isfinite(numbers[0]) || !std::isfinite(numbers[1]))
      throw CaseError(fmt::format("{}: {}:{}: expected two numbers, x and y in m, found '{}'", key_path, file.string(),
                                  number, line));
    points.push_back({numbers[0], numbers[1]});
  }
  if (in.bad()) throw CaseError(fmt::format("{}: cannot read '{}'", key_path, file.string()));
  return points;
}

}  // namespace granflow

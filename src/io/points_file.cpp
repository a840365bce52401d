#include "io/points_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <cmath>
#include <sstream>
#include <string_view>

#include "io/case_error.hpp"
#include "io/table_reader.hpp"
#include "io/text_file.hpp"

namespace granflow {

namespace {

// The numbers of a line: fields separated by blanks, by one comma or semicolon, or by both ("1, 2").
// False where a field is not a number or is empty ("0.2,,0", a leading or trailing comma), as a column
// left blank in a spreadsheet would shift the numbers that follow. `any` tells whether some field is one.
bool parse_numbers(std::string_view line, std::vector<double>& out, bool& any) {
  out.clear();
  any = false;
  bool all = true;
  size_t k = 0;
  auto blank = [](char ch) { return ch == ' ' || ch == '\t' || ch == '\r'; };
  auto delimiter = [](char ch) { return ch == ',' || ch == ';'; };
  // Skips the separator after a field (or before the first): blanks, at most one delimiter, blanks.
  // False where a delimiter has no field on one side of it.
  auto skip_separator = [&](bool after_field) {
    while (k < line.size() && blank(line[k])) ++k;
    if (k < line.size() && delimiter(line[k])) {
      ++k;
      while (k < line.size() && blank(line[k])) ++k;
      return after_field && k < line.size() && !delimiter(line[k]);
    }
    return true;
  };
  if (!skip_separator(false)) all = false;
  while (k < line.size()) {
    size_t end = k;
    while (end < line.size() && !blank(line[end]) && !delimiter(line[end])) ++end;
    const std::string_view field = line.substr(k, end - k);
    const std::optional<double> value = number_in(field);  // none for an empty field: ',,'
    if (!value)
      all = false;
    else
      any = true;
    out.push_back(value.value_or(0.0));
    k = end;
    if (!skip_separator(true)) all = false;
  }
  return all;
}

}  // namespace

std::vector<std::array<double, 2>> read_points_file(const std::filesystem::path& file, const std::string& key_path) {
  // Some 30 bytes a point: room for eight million of them.
  constexpr std::size_t limit = std::size_t(256) << 20;
  std::istringstream in(read_named_file(file, limit, key_path, "a file of points"));
  std::vector<std::array<double, 2>> points;
  std::vector<double> numbers;
  bool first = true;
  long number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (number == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);  // a UTF-8 byte-order mark
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    bool any = false;
    const bool parsed = parse_numbers(line, numbers, any);
    // A header names its columns: not one of its fields is a number ("x,y"; "0.1,O.2" is a typo).
    const bool header = first && !any;
    first = false;
    if (header) continue;
    if (!parsed || numbers.size() != 2 || !std::isfinite(numbers[0]) || !std::isfinite(numbers[1]))
      throw CaseError(fmt::format("{}: {}:{}: expected two numbers, x and y in m, found '{}'", key_path, file.string(),
                                  number, printable(line, 80)));
    for (const double x : {numbers[0], numbers[1]})
      if (auto problem = magnitude_problem(x); !problem.empty())
        throw CaseError(fmt::format("{}: {}:{}: {}", key_path, file.string(), number, problem));
    points.push_back({numbers[0], numbers[1]});
  }
  return points;
}

}  // namespace granflow

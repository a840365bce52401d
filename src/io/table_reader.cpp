#include "io/table_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "io/case_error.hpp"

namespace granflow {

namespace {
// A TOML number as a double: an integer too large for a double to hold exactly (toml++ then gives
// none) is still the number it says, for the range checks to name.
std::optional<double> number_of(const toml::node& n) {
  if (auto v = n.value<double>()) return v;
  if (const auto* i = n.as_integer()) return double(i->get());
  return std::nullopt;
}
}  // namespace

std::string TableReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool TableReader::has(std::string_view key) const { return table_ && table_->contains(key); }

const toml::node* TableReader::get(std::string_view key) {
  used_.insert(std::string(key));
  if (!table_) return nullptr;
  return table_->get(key);
}

void TableReader::type_error(std::string_view key, const char* expected) const {
  throw CaseError(fmt::format("{}: expected {}", key_path(key), expected));
}

void TableReader::missing(std::string_view key, std::string_view what) const {
  throw CaseError(fmt::format("{}: missing ({}){}", key_path(key), what, misspelling_of(key)));
}

namespace {
// Tolerances may be as small as the user likes: PETSc's own absolute tolerance is 1e-50.
bool is_tolerance(std::string_view key) { return key == "atol" || key == "rtol" || key.ends_with("_tolerance"); }
}  // namespace

std::string magnitude_problem(double value) {
  const double a = std::abs(value);
  if (a > largest_magnitude || (a > 0 && a < smallest_magnitude))
    return fmt::format("{} is beyond the magnitudes granflow computes with ({} to {}, or 0)", value, smallest_magnitude,
                       largest_magnitude);
  return {};
}

void TableReader::require_magnitude(std::string_view key, double value) const {
  if (is_tolerance(key) && std::abs(value) <= largest_magnitude) return;
  if (auto problem = magnitude_problem(value); !problem.empty())
    throw CaseError(fmt::format("{}: {}", key_path(key), problem));
}

namespace {
// Edits (insertions, deletions, substitutions, swaps of neighbours) that turn a into b.
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}
}  // namespace

std::string TableReader::misspelling_of(std::string_view key) const {
  if (!table_) return {};
  const size_t most = key.size() < 4 ? 1 : 2;
  for (const auto& [k, v] : *table_)
    if (!used_.count(k.str()) && edit_distance(k.str(), key) <= most)
      return fmt::format("; {} is not a key: {} misspelt?", key_path(k.str()), key);
  return {};
}

std::optional<double> TableReader::optional_number(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  if (auto v = number_of(*n)) {
    if (!std::isfinite(*v)) type_error(key, "a finite number");
    require_magnitude(key, *v);
    return *v;
  }
  type_error(key, "a number");
}

double TableReader::number(std::string_view key, double fallback) {
  return optional_number(key).value_or(fallback);
}

double TableReader::required_number(std::string_view key) {
  auto v = optional_number(key);
  if (!v) missing(key, "a number is required");
  return *v;
}

long TableReader::integer(std::string_view key, long fallback) {
  const toml::node* n = get(key);
  if (!n) return fallback;
  if (auto v = n->value_exact<int64_t>()) return long(*v);
  // A whole number written as a float (1e5, 100.0) is the integer it says, as in mesh.cells; the
  // bound keeps it exact in a double, and each key's own range check follows.
  if (const auto* f = n->as_floating_point()) {
    const double x = f->get();
    if (std::isfinite(x) && x == std::floor(x) && std::abs(x) <= 9.0e15) return long(x);
  }
  type_error(key, "an integer (a whole number)");
}

int TableReader::integer_in(std::string_view key, int fallback, long lo, long hi) {
  const long value = integer(key, fallback);
  if (value < lo || value > hi)
    throw CaseError(fmt::format("{}: {} is invalid, must be in [{}, {}]", key_path(key), value, lo, hi));
  return int(value);
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* n = get(key);
  if (!n) return fallback;
  if (auto v = n->value_exact<bool>()) return *v;
  type_error(key, "true or false");
}

std::string TableReader::string(std::string_view key, std::string fallback) {
  const toml::node* n = get(key);
  if (!n) return fallback;
  if (auto v = n->value_exact<std::string>()) return *v;
  type_error(key, "a string");
}

std::string TableReader::required_string(std::string_view key) {
  if (!has(key)) missing(key, "a string is required");
  return string(key, {});
}

std::string TableReader::choice(std::string_view key, std::string fallback,
                                std::initializer_list<std::string_view> allowed) {
  std::string v = string(key, std::move(fallback));
  for (auto a : allowed)
    if (v == a) return v;
  std::string list;
  for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  if (!has(key)) missing(key, "one of: " + list);
  throw CaseError(fmt::format("{}: '{}' is not one of: {}", key_path(key), v, list));
}

std::vector<double> TableReader::numbers(std::string_view key, std::vector<double> fallback, size_t min_size) {
  const toml::node* n = get(key);
  if (!n) return fallback;
  const toml::array* arr = n->as_array();
  if (!arr) type_error(key, "an array of numbers");
  std::vector<double> out;
  for (const auto& e : *arr) {
    auto v = number_of(e);
    if (!v) type_error(key, "an array of numbers");
    if (!std::isfinite(*v)) type_error(key, "an array of finite numbers");
    require_magnitude(key, *v);
    out.push_back(*v);
  }
  if (out.size() < min_size) type_error(key, fmt::format("at least {} numbers", min_size).c_str());
  return out;
}

std::array<double, 2> TableReader::pair(std::string_view key, std::array<double, 2> fallback) {
  if (!has(key)) {
    get(key);
    return fallback;
  }
  auto v = numbers(key, {}, 0);
  if (v.size() != 2) type_error(key, "two numbers [x, y]");
  return {v[0], v[1]};
}

std::array<double, 2> TableReader::required_pair(std::string_view key) {
  if (!has(key)) missing(key, "two numbers [x, y] are required");
  return pair(key, {});
}

std::vector<std::array<double, 2>> TableReader::pairs(std::string_view key, size_t min_size) {
  const toml::node* n = get(key);
  if (!n) missing(key, "a list of [x, y] points is required");
  const toml::array* arr = n->as_array();
  if (!arr) type_error(key, "a list of [x, y] points");
  std::vector<std::array<double, 2>> out;
  for (const auto& e : *arr) {
    const toml::array* pt = e.as_array();
    if (!pt || pt->size() != 2) type_error(key, "a list of [x, y] points");
    auto x = number_of((*pt)[0]), y = number_of((*pt)[1]);
    if (!x || !y) type_error(key, "a list of [x, y] points");
    if (!std::isfinite(*x) || !std::isfinite(*y)) type_error(key, "a list of [x, y] points of finite numbers");
    require_magnitude(key, *x);
    require_magnitude(key, *y);
    out.push_back({*x, *y});
  }
  if (out.size() < min_size) type_error(key, fmt::format("at least {} points", min_size).c_str());
  return out;
}

std::vector<std::vector<double>> TableReader::grid(std::string_view key, size_t min_rows, size_t min_columns) {
  const toml::node* n = get(key);
  const auto expected = fmt::format("an array of at least {} rows of numbers, each at least {} long", min_rows,
                                    min_columns);
  if (!n) missing(key, expected);
  const toml::array* arr = n->as_array();
  if (!arr || arr->size() < min_rows) type_error(key, expected.c_str());
  std::vector<std::vector<double>> out;
  for (const auto& e : *arr) {
    const toml::array* row = e.as_array();
    if (!row) type_error(key, expected.c_str());
    auto& values = out.emplace_back();
    for (const auto& v : *row) {
      const auto x = number_of(v);
      if (!x || !std::isfinite(*x)) type_error(key, expected.c_str());
      require_magnitude(key, *x);
      values.push_back(*x);
    }
    if (values.size() < min_columns) type_error(key, expected.c_str());
    if (values.size() != out.front().size())
      throw CaseError(fmt::format("{}: row {} holds {} numbers and row 1 {}: the rows are of one length", key_path(key),
                                  out.size(), values.size(), out.front().size()));
  }
  return out;
}

TableReader TableReader::table(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return TableReader(nullptr, key_path(key));
  const toml::table* t = n->as_table();
  if (!t) type_error(key, "a table");
  return TableReader(t, key_path(key));
}

std::vector<TableReader> TableReader::tables(std::string_view key) {
  const toml::node* n = get(key);
  std::vector<TableReader> out;
  if (!n) return out;
  const toml::array* arr = n->as_array();
  if (!arr) type_error(key, "an array of tables ([[...]])");
  int index = 0;
  for (const auto& e : *arr) {
    const toml::table* t = e.as_table();
    if (!t) type_error(key, "an array of tables ([[...]])");
    out.emplace_back(t, fmt::format("{}[{}]", key_path(key), index++));
  }
  return out;
}

void TableReader::finish() const {
  if (!table_) return;
  for (const auto& [k, v] : *table_) {
    if (!used_.count(k.str())) {
      std::string known;
      for (const auto& u : used_) known += (known.empty() ? "" : ", ") + u;
      throw CaseError(fmt::format("{}: unknown key (known keys here: {})", key_path(k.str()), known));
    }
  }
}

void TableReader::require_range(std::string_view key, double value, double lo, double hi, const char* what) const {
  if (!(value >= lo && value <= hi)) {
    std::string range = what ? what : fmt::format("in [{}, {}]", lo, hi);
    throw CaseError(fmt::format("{}: {} is invalid, must be {}", key_path(key), value, range));
  }
}

}  // namespace granflow

#pragma once
// Reads one TOML table of a case file key by key. Every key read is recorded, so finish() can report
// any key that no reader asked for (a misspelt or unsupported key is an error, never ignored).
#include <array>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace granflow {

// Inputs beyond these magnitudes overflow or underflow in the products the solver forms (a pressure
// rho g L, a viscous coefficient mu dt / h^2), and the first solve would fail without naming the key.
inline constexpr double largest_magnitude = 1e30;
inline constexpr double smallest_magnitude = 1e-30;
// What a value beyond them is said to be, after the key (and file) it came from; empty within them.
std::string magnitude_problem(double value);

class TableReader {
 public:
  TableReader(const toml::table* table, std::string path) : table_(table), path_(std::move(path)) {}

  bool present() const { return table_ != nullptr; }
  bool has(std::string_view key) const;
  const std::string& path() const { return path_; }
  std::string key_path(std::string_view key) const;

  double number(std::string_view key, double fallback);
  double required_number(std::string_view key);
  std::optional<double> optional_number(std::string_view key);
  long integer(std::string_view key, long fallback);
  // An integer that must lie in [lo, hi], checked before it is narrowed to int.
  int integer_in(std::string_view key, int fallback, long lo, long hi);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, std::string fallback);
  std::string required_string(std::string_view key);
  // A string that must be one of `allowed`.
  std::string choice(std::string_view key, std::string fallback, std::initializer_list<std::string_view> allowed);
  std::vector<double> numbers(std::string_view key, std::vector<double> fallback, size_t min_size = 0);
  std::array<double, 2> pair(std::string_view key, std::array<double, 2> fallback);
  std::array<double, 2> required_pair(std::string_view key);
  // An array of [x, y] pairs, at least min_size of them.
  std::vector<std::array<double, 2>> pairs(std::string_view key, size_t min_size);
  // A required grid of finite numbers: an array of rows, each an array of numbers, all of one length,
  // at least min_rows of at least min_columns.
  std::vector<std::vector<double>> grid(std::string_view key, size_t min_rows, size_t min_columns);

  // A sub-table; absent gives a reader with present() == false whose reads return their fallbacks.
  TableReader table(std::string_view key);
  // An array of tables ([[key]]).
  std::vector<TableReader> tables(std::string_view key);

  // A key this table knows though it was not read here (a polygon's points_file, taken before; a
  // wall's friction keys, looked for with has()), to be named among the known keys of finish()'s message.
  void known_elsewhere(std::string_view key) { used_.insert(std::string(key)); }
  // Throws CaseError naming the first key present in the table that nobody read.
  void finish() const;

  // For a message that `key` is missing: where the table holds a key nobody has read that is `key`
  // misspelt (one or two letters off, or two swapped), "; PATH.KEY2 is not a key: KEY misspelt?",
  // else empty. A required key missing is then reported as the misspelling it is.
  std::string misspelling_of(std::string_view key) const;

  // Checks that value lies in [lo, hi] (use +-inf for open ends); throws naming the key.
  void require_range(std::string_view key, double value, double lo, double hi, const char* what = nullptr) const;

 private:
  const toml::node* get(std::string_view key);
  // Throws naming the key when a nonzero number lies outside [1e-30, 1e30] in magnitude (tolerances
  // may be smaller).
  void require_magnitude(std::string_view key, double value) const;
  [[noreturn]] void type_error(std::string_view key, const char* expected) const;
  [[noreturn]] void missing(std::string_view key, std::string_view what) const;

  const toml::table* table_;
  std::string path_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace granflow

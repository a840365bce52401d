#include "io/height_map_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <string_view>

#include "io/case_error.hpp"
#include "io/table_reader.hpp"
#include "io/text_file.hpp"

namespace granflow {

namespace {

std::string lower_case(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return out;
}

}  // namespace

interface::HeightMap read_height_map_file(const std::filesystem::path& file, const std::string& key_path) {
  constexpr std::size_t limit = std::size_t(256) << 20;  // some 10 bytes a height: 25 million of them
  const std::string whole_text = read_named_file(file, limit, key_path, "a height map");
  const std::string_view text = whole_text;
  auto where = [&](long line) { return fmt::format("{}: {}:{}", key_path, file.string(), line); };
  // The header: lines whose first field is not a number, each a key and its number.
  std::map<std::string, double> header;
  size_t at = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte-order mark
  long line = 0;
  auto blank = [](char ch) { return ch == ' ' || ch == '\t' || ch == '\r'; };
  auto next_field = [&](size_t& k, size_t end) {
    while (k < end && blank(text[k])) ++k;
    const size_t from = k;
    while (k < end && !blank(text[k])) ++k;
    return text.substr(from, k - from);
  };
  while (at < text.size()) {
    const size_t end = std::min(text.find('\n', at), text.size());
    size_t k = at;
    const std::string_view key = next_field(k, end);
    if (!key.empty() && number_in(key)) break;  // the first height
    ++line;
    const std::string_view whole = text.substr(at, end - at);
    at = end + 1;
    if (key.empty()) continue;
    const std::string_view value = next_field(k, end);
    const auto number = number_in(value);
    if (!number || !next_field(k, end).empty())
      throw CaseError(fmt::format("{}: expected a header key and its number (ncols, nrows, xllcorner, yllcorner, "
                                  "cellsize, NODATA_value), found '{}'", where(line), printable(whole, 40)));
    const std::string name = lower_case(key);
    static const char* const known[] = {"ncols", "nrows", "xllcorner", "xllcenter", "yllcorner", "yllcenter",
                                        "cellsize", "dx", "dy", "nodata_value"};
    if (std::find(std::begin(known), std::end(known), name) == std::end(known))
      throw CaseError(fmt::format("{}: unknown header key '{}' (an ESRI ASCII grid has ncols, nrows, xllcorner or "
                                  "xllcenter, yllcorner or yllcenter, cellsize or dx and dy, NODATA_value)",
                                  where(line), printable(key, 40)));
    if (!header.emplace(name, *number).second)
      throw CaseError(fmt::format("{}: '{}' given twice", where(line), printable(key, 40)));
  }
  auto need = [&](const char* name) {
    const auto it = header.find(name);
    if (it == header.end())
      throw CaseError(fmt::format("{}: '{}' has no {} in its header (an ESRI ASCII grid's)", key_path, file.string(),
                                  name));
    return it->second;
  };
  auto count = [&](const char* name) {
    const double n = need(name);
    if (!(n >= 2 && n <= 1e8 && n == std::floor(n)))
      throw CaseError(fmt::format("{}: '{}': {} is {}, not a whole number of at least 2", key_path, file.string(), name,
                                  n));
    return int(n);
  };
  auto one_of = [&](const char* corner, const char* centre) {
    const bool has_corner = header.count(corner) != 0, has_centre = header.count(centre) != 0;
    if (has_corner == has_centre)
      throw CaseError(fmt::format("{}: '{}' needs one of {} and {} in its header", key_path, file.string(), corner,
                                  centre));
    return std::pair{has_corner, has_corner ? header.at(corner) : header.at(centre)};
  };
  interface::HeightMap map;
  map.nx = count("ncols");
  map.nz = count("nrows");
  const auto [x_corner, x0] = one_of("xllcorner", "xllcenter");
  const auto [z_corner, z0] = one_of("yllcorner", "yllcenter");
  const bool square = header.count("cellsize") != 0;
  if (square == (header.count("dx") != 0 || header.count("dy") != 0))
    throw CaseError(fmt::format("{}: '{}' needs cellsize, or dx and dy, in its header", key_path, file.string()));
  map.spacing = square ? std::array{header.at("cellsize"), header.at("cellsize")} : std::array{need("dx"), need("dy")};
  for (const double d : map.spacing)
    if (!(d > 0.0) || !std::isfinite(d))
      throw CaseError(fmt::format("{}: '{}': the cell size {} is not positive", key_path, file.string(), d));
  map.origin = {x0 + (x_corner ? 0.5 * map.spacing[0] : 0.0), z0 + (z_corner ? 0.5 * map.spacing[1] : 0.0)};
  for (const double v : {map.origin[0], map.origin[1]})
    if (auto problem = magnitude_problem(v); !problem.empty())
      throw CaseError(fmt::format("{}: '{}': {}", key_path, file.string(), problem));
  const bool has_nodata = header.count("nodata_value") != 0;
  const double nodata = has_nodata ? header.at("nodata_value") : 0.0;
  // The heights, row by row from the north; stored from the south (z up from the origin). Each takes
  // two bytes at least (a digit and a blank): a header asking for more than the file holds is refused
  // before the heights are made room for.
  const size_t rest = at < text.size() ? text.size() - at : 0;
  if (double(map.nx) * map.nz > 0.5 * double(rest) + 1.0)
    throw CaseError(fmt::format("{}: '{}' asks for ncols x nrows = {} x {} heights, more than the rest of the file "
                                "({} bytes) can hold", key_path, file.string(), map.nx, map.nz, rest));
  map.heights.assign(size_t(map.nx) * map.nz, 0.0);
  size_t read_count = 0;
  const size_t total = map.heights.size();
  while (at < text.size()) {
    const size_t end = std::min(text.find('\n', at), text.size());
    ++line;
    size_t k = at;
    for (std::string_view field = next_field(k, end); !field.empty(); field = next_field(k, end)) {
      const auto h = number_in(field);
      if (read_count == total)
        throw CaseError(fmt::format("{}: more heights than ncols x nrows = {} x {}", where(line), map.nx, map.nz));
      const int row = int(read_count / map.nx), col = int(read_count % map.nx);
      if (h && has_nodata && (*h == nodata || (std::isnan(nodata) && std::isnan(*h))))
        throw CaseError(fmt::format("{}: no height (NODATA) at row {}, column {}: a height map needs every node "
                                    "(fill the model's gaps first)", where(line), row + 1, col + 1));
      if (!h || !std::isfinite(*h))
        throw CaseError(fmt::format("{}: expected a height, found '{}'", where(line), printable(field, 40)));
      if (auto problem = magnitude_problem(*h); !problem.empty())
        throw CaseError(fmt::format("{}: {}", where(line), problem));
      map.heights[size_t(map.nz - 1 - row) * map.nx + col] = *h;
      ++read_count;
    }
    at = end + 1;
  }
  if (read_count != total)
    throw CaseError(fmt::format("{}: '{}' holds {} heights, not ncols x nrows = {} x {} = {}", key_path,
                                file.string(), read_count, map.nx, map.nz, total));
  return map;
}

}  // namespace granflow

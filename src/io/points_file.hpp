#pragma once
// A polygon's vertices from a text file (`points_file` of a shape): one point per line, x and y
// separated by a comma, a semicolon or blanks, as a terrain profile or a surveyed outline is exported.
// Lines that are empty or start with '#' are skipped, and so is a first line of which no field is a
// number (a header such as "x,y"); a UTF-8 byte-order mark is ignored.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace granflow {

// Throws CaseError naming `key_path` and the file where the file cannot be read, and the file and
// line where a line is not two finite numbers.
std::vector<std::array<double, 2>> read_points_file(const std::filesystem::path& file, const std::string& key_path);

}  // namespace granflow

#pragma once
// Files are written whole: into a temporary beside the target, then renamed over it, so a killed run
// never leaves a torn file.
#include <filesystem>
#include <functional>
#include <ostream>

namespace granflow {
void write_file_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& body);
}

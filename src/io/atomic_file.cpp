#include "io/atomic_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>

namespace granflow {
void write_file_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& body) {
  const auto tmp = target.parent_path() / fmt::format(".{}.tmp{}", target.filename().string(), ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error(fmt::format("cannot write {} (through {})", target.string(), tmp.filename().string()));
    body(out);
    out.flush();
    if (!out) throw std::runtime_error(fmt::format("writing {} failed", tmp.string()));
  }
  std::filesystem::rename(tmp, target);
}
}  // namespace granflow

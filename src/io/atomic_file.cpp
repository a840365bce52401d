#include "io/atomic_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace granflow {
void write_file_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& body) {
  const auto tmp = target.parent_path() / fmt::format(".{}.tmp{}", target.filename().string(), ::getpid());
  // The reason, as the system gave it (a full disk, a quota); the stream itself keeps none.
  auto failed = [&](const char* what) {
    const int error = errno;
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);  // no half-written file is left behind
    return std::runtime_error(fmt::format("cannot {} {}{}", what, target.string(),
                                          error ? fmt::format(": {}", std::strerror(error)) : std::string()));
  };
  {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw failed("write");
    try {
      body(out);
    } catch (...) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw;
    }
    out.flush();
    out.close();
    if (!out) throw failed("finish writing");
  }
  std::filesystem::rename(tmp, target);
}
}  // namespace granflow

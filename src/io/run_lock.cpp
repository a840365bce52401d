#include "io/run_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace granflow {

RunLock::~RunLock() {
  if (fd_ >= 0) close(fd_);
}

std::string RunLock::take(const std::filesystem::path& dir) {
  if (held() || unlockable_) return {};
  // A directory that cannot be locked (a file system without locks, a directory that cannot be
  // opened for reading) does not stop the run: it goes on unguarded, and says so once.
  auto unguarded = [&](int error) {
    unlockable_ = true;
    fmt::print(stderr, "warning: -o {}: cannot lock the output directory ({}): a second run into it would not be "
                       "refused\n", dir.string(), std::strerror(error));
    return std::string();
  };
  const int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return unguarded(errno);
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    close(fd);
    if (error == EWOULDBLOCK)
      return fmt::format("-o {}: another granflow run is writing into this directory; wait for it to end, or choose "
                         "another directory with -o",
                         dir.string());
    return unguarded(error);
  }
  fd_ = fd;
  return {};
}

}  // namespace granflow

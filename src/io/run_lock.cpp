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
  // A directory that cannot be opened to be read cannot be checked for an earlier run either: bad
  // input, as before there was a lock.
  const int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return fmt::format("-o {}: cannot open the output directory: {}", dir.string(), std::strerror(errno));
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    close(fd);
    if (error == EWOULDBLOCK)
      return fmt::format("-o {}: another granflow run is writing into this directory; wait for it to end, or choose "
                         "another directory with -o",
                         dir.string());
    // A file system that does not lock directories (NFS, which emulates flock with byte-range locks
    // on files open for writing, fails with EBADF) does not stop the run: it goes on unguarded, and
    // says so once.
    if (error == EBADF || error == ENOLCK || error == EOPNOTSUPP || error == ENOTSUP || error == ENOSYS) {
      unlockable_ = true;
      fmt::print(stderr, "warning: -o {}: this file system does not lock the output directory ({}): a second run into "
                         "it would not be refused\n", dir.string(), std::strerror(error));
      return {};
    }
    return fmt::format("-o {}: cannot lock the output directory: {}", dir.string(), std::strerror(error));
  }
  fd_ = fd;
  return {};
}

}  // namespace granflow

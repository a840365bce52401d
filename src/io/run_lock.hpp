#pragma once
// One run at a time in an output directory. Two runs writing into one directory would mix their
// fields, histories and checkpoints, each unaware of the other; the run holds an exclusive lock on the
// directory (flock on the directory itself, so no file is added to it) for as long as it lives, and a
// second run is refused. The lock goes with the process however it ends, killed or crashed. It holds
// between runs on one machine: a network file system locks a directory only locally.
#include <filesystem>
#include <string>

namespace granflow {

class RunLock {
 public:
  RunLock() = default;
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  // Takes the lock on `dir`, which must exist: "" once held, or "" with a warning if the directory
  // cannot be locked at all; the message naming the directory if another run holds it.
  std::string take(const std::filesystem::path& dir);
  bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
  bool unlockable_ = false;  // warned of; not tried again
};

}  // namespace granflow

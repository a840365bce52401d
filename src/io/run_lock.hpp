#pragma once
// One run at a time in an output directory. Two runs writing into one directory would mix their
// fields, histories and checkpoints, each unaware of the other; the run holds an exclusive lock on the
// directory (flock on the directory itself, so no file is added to it) for as long as it lives, and a
// second run is refused. The lock goes with the process however it ends, killed or crashed. A file
// system that does not lock directories (NFS, commonly) leaves the run unguarded, with a warning.
#include <filesystem>
#include <string>

namespace granflow {

class RunLock {
 public:
  RunLock() = default;
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  // Takes the lock on `dir`, which must exist: "" once held, or "" with a warning if its file system
  // does not lock directories; else the message naming the directory (another run holds it, or it
  // cannot be opened).
  std::string take(const std::filesystem::path& dir);
  bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
  bool unlockable_ = false;  // warned of; not tried again
};

}  // namespace granflow

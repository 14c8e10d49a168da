#pragma once
// One writer per output folder. `viqu run`, `viqu slam`, `viqu view` and `viqu sweep` hold an
// OutputLock on their --out folder while they write it; a second process asking for the same
// folder is refused (InputError, exit 2) naming the holder's pid, where before both ran, both
// printed their outputs, and the folder held one of them.
//
// The lock is flock(2) on a lock file beside the folder, PARENT/.NAME.viqu-lock (not inside it:
// a run replaces its folder as a whole). The kernel releases it when its holder ends, killed or
// not, so a stale lock never blocks a later run; the holder removes the file when it lets go.
// On a file system without flock (some NFS or Lustre mounts) the lock cannot be taken: a warning
// says so and the command goes on unguarded.
#include <string>

namespace viqu {

class OutputLock {
 public:
  // Takes the lock for `dir` (its parent folder is created when missing); `what` names the
  // command in the holder's record ("viqu run"). Throws InputError when another process holds it.
  OutputLock(const std::string& dir, const std::string& what);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  // The lock file's path.
  const std::string& path() const { return path_; }
  // Whether the lock is held (false where the file system has no flock).
  bool held() const { return fd_ >= 0; }

 private:
  std::string path_;
  int fd_ = -1;
};

// PARENT/.NAME.viqu-lock for folder PARENT/NAME.
std::string OutputLockPath(const std::string& dir);

}  // namespace viqu

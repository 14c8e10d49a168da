#include "common/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "common/errors.h"

namespace viqu {
namespace fs = std::filesystem;

namespace {

// Attempts at a lock file that its holder removed between our open and our flock (each attempt
// finds a newer file; more than a few in a row would take runs starting and ending in a loop).
constexpr int kLockAttempts = 20;

std::string ReadHolder(int fd) {
  char buf[256] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string text = n > 0 ? std::string(buf, static_cast<size_t>(n)) : std::string();
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

}  // namespace

std::string OutputLockPath(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (!p.has_filename() && p.has_relative_path()) p = p.parent_path();
  return (p.parent_path() / ("." + p.filename().string() + ".viqu-lock")).string();
}

OutputLock::OutputLock(const std::string& dir, const std::string& what) : path_(OutputLockPath(dir)) {
  std::error_code ec;
  const fs::path parent = fs::path(path_).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  for (int attempt = 0; attempt < kLockAttempts; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError("cannot lock output folder " + dir + " (" + path_ + "): " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      if (e == EWOULDBLOCK) {
        const std::string holder = ReadHolder(fd);
        ::close(fd);
        throw InputError("output folder " + dir + " is in use by " +
                         (holder.empty() ? std::string("another viqu process") : holder) +
                         " (lock " + path_ + "); wait for it to end, or choose another --out");
      }
      ::close(fd);
      std::fprintf(stderr, "viqu: warning: %s: cannot lock the output folder (%s): another command writing it at the same time "
                   "would not be refused\n", dir.c_str(), std::strerror(e));
      return;
    }
    // The holder before us removes the file when it lets go: a lock on a file no longer at the
    // path guards nothing; take the new file's instead.
    struct stat held {}, now {};
    if (::fstat(fd, &held) != 0 || ::stat(path_.c_str(), &now) != 0 || held.st_ino != now.st_ino ||
        held.st_dev != now.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string record = what + " (pid " + std::to_string(::getpid()) + ")\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, record.data(), record.size(), 0) != static_cast<ssize_t>(record.size())) {
      // The record is for messages only; the lock holds without it.
    }
    fd_ = fd;
    return;
  }
  throw InputError("cannot lock output folder " + dir + " (" + path_ + "): its lock file keeps changing");
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  // Removed while still locked, so that no process can lock this file after we let go and
  // believe it guards the folder (it checks the path still names the file it locked).
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace viqu

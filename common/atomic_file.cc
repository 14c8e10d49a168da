#include "common/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "common/atomic_output_file.h"
#include "common/errors.h"

namespace viqu {

std::string TempPathFor(const std::string& path) {
  return path + ".tmp." + std::to_string(::getpid());
}

void CommitTempFile(const std::string& tmp_path, const std::string& final_path) {
  if (std::rename(tmp_path.c_str(), final_path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp_path.c_str());
    throw RunError("cannot rename " + tmp_path + " to " + final_path + ": " + why);
  }
}

void CommitTempDirectory(const std::string& from, const std::string& to) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string old_dir = to + ".old." + std::to_string(::getpid());
  const bool had_old = fs::exists(to, ec);
  if (had_old) {
    fs::rename(to, old_dir, ec);
    if (ec) throw RunError("cannot move the old " + to + " aside: " + ec.message());
  }
  fs::rename(from, to, ec);
  if (ec) {
    const std::string why = ec.message();
    std::error_code back;
    if (had_old) fs::rename(old_dir, to, back);  // the old one back in place
    throw RunError("cannot rename " + from + " to " + to + ": " + why + (had_old && back ? "; the previous " + to +
                   " is in " + old_dir : ""));
  }
  if (had_old) fs::remove_all(old_dir, ec);
}

void WriteFileAtomic(const std::string& path, const std::string& content) {
  AtomicOutputFile out(path);
  out.Write(content);
  out.Commit();
}

}  // namespace viqu

#include "common/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

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

void WriteFileAtomic(const std::string& path, const std::string& content) {
  AtomicOutputFile out(path);
  out.Write(content);
  out.Commit();
}

}  // namespace viqu

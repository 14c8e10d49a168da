#include "common/atomic_output_file.h"

#include <cerrno>
#include <cstring>

#include "common/atomic_file.h"
#include "common/errors.h"

namespace viqu {

AtomicOutputFile::AtomicOutputFile(const std::string& final_path)
    : final_path_(final_path), temp_path_(TempPathFor(final_path)) {
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (file_ == nullptr) throw RunError("cannot write " + temp_path_ + ": " + std::strerror(errno));
}

AtomicOutputFile::~AtomicOutputFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) std::remove(temp_path_.c_str());
}

void AtomicOutputFile::Write(const std::string& text) {
  if (file_ == nullptr) throw RunError("write to " + final_path_ + " after it was committed");
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) {
    throw RunError("write failed for " + temp_path_ + ": " + std::strerror(errno));
  }
}

void AtomicOutputFile::Commit() {
  if (committed_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fflush(f) != 0 || std::ferror(f) != 0) {
    const std::string why = std::strerror(errno);
    std::fclose(f);
    throw RunError("write failed for " + temp_path_ + ": " + why);
  }
  if (std::fclose(f) != 0) throw RunError("cannot close " + temp_path_ + ": " + std::strerror(errno));
  CommitTempFile(temp_path_, final_path_);
  committed_ = true;
}

}  // namespace viqu

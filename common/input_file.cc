#include "common/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "common/errors.h"
#include "common/stop_signal.h"

namespace viqu {
namespace {

// Bytes read at a time; a stop signal is looked at between two reads.
constexpr size_t kChunkBytes = size_t{1} << 16;

std::string MiB(uintmax_t bytes) {
  return bytes >= (uintmax_t{1} << 20) ? std::to_string(bytes >> 20) + " MiB" : std::to_string(bytes) + " bytes";
}

void ThrowIfStopped(const std::string& path) {
  if (const int signal = StopSignal()) throw Stopped(signal, "stopped by " + std::string(SignalName(signal)) + " while reading " + path);
}

}  // namespace

uintmax_t CheckInputFile(const std::string& path, uintmax_t max_bytes, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int e = errno;
    if (e == ENOENT) {
      struct stat lst {};
      if (::lstat(path.c_str(), &lst) == 0) throw InputError(path + ": " + what + " is a link to nothing (dangling link)");
      throw InputError(path + ": file not found");
    }
    if (e == ELOOP) throw InputError(path + ": " + what + " is a loop of links");
    throw InputError(path + ": cannot read " + what + ": " + std::strerror(e));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a directory, not a " + what);
  if (!S_ISREG(st.st_mode)) {
    throw InputError(path + ": not a regular file (a device, pipe or socket may never end); expected a " + what);
  }
  const uintmax_t size = static_cast<uintmax_t>(st.st_size);
  if (size > max_bytes) throw InputError(path + ": larger than " + MiB(max_bytes) + " (" + MiB(size) + "): too large for a " + what);
  return size;
}

std::string ReadInputFile(const std::string& path, uintmax_t max_bytes, const std::string& what) {
  const uintmax_t size = CheckInputFile(path, max_bytes, what);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path + ": cannot open " + what + ": " + std::strerror(errno));
  std::string text;
  text.reserve(static_cast<size_t>(size));
  char chunk[kChunkBytes];
  while (true) {
    ThrowIfStopped(path);
    const size_t n = std::fread(chunk, 1, sizeof chunk, f);
    text.append(chunk, n);
    if (text.size() > max_bytes) {
      std::fclose(f);
      throw InputError(path + ": larger than " + MiB(max_bytes) + ": too large for a " + what);
    }
    if (n < sizeof chunk) break;
  }
  const bool error = std::ferror(f) != 0;
  std::fclose(f);
  if (error) throw InputError(path + ": read error in " + what);
  return text;
}

InputLines::InputLines(std::string path, uintmax_t max_bytes, const std::string& what)
    : path_(std::move(path)), max_bytes_(max_bytes) {
  CheckInputFile(path_, max_bytes_, what);
  file_ = std::fopen(path_.c_str(), "rb");
  if (!file_) throw InputError(path_ + ": cannot open " + what + ": " + std::strerror(errno));
}

InputLines::~InputLines() {
  if (file_) std::fclose(file_);
}

bool InputLines::Fill() {
  if (eof_) return false;
  ThrowIfStopped(path_);
  char chunk[kChunkBytes];
  const size_t n = std::fread(chunk, 1, sizeof chunk, file_);
  if (n < sizeof chunk) {
    if (std::ferror(file_)) throw InputError(path_ + ": read error");
    eof_ = true;
  }
  read_ += n;
  if (read_ > max_bytes_) throw InputError(path_ + ": grew past " + MiB(max_bytes_) + " while it was read");
  buf_.erase(0, pos_);
  pos_ = 0;
  buf_.append(chunk, n);
  return n > 0;
}

bool InputLines::Next(std::string* line) {
  while (true) {
    const size_t nl = buf_.find('\n', pos_);
    if (nl != std::string::npos) {
      if (nl - pos_ > kMaxInputLineBytes) break;
      line->assign(buf_, pos_, nl - pos_);
      pos_ = nl + 1;
      ++line_;
      return true;
    }
    if (buf_.size() - pos_ > kMaxInputLineBytes) break;
    if (!Fill()) {
      if (pos_ >= buf_.size()) return false;
      line->assign(buf_, pos_, std::string::npos);  // the last line, without a line break
      pos_ = buf_.size();
      ++line_;
      return true;
    }
  }
  throw InputError(path_ + ":" + std::to_string(line_ + 1) + ": line longer than " + MiB(kMaxInputLineBytes) +
                   " (a binary file, or no line breaks?)");
}

}  // namespace viqu

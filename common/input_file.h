#pragma once
// Reading a user's input file without trusting it: only a regular file is read (a device or a
// pipe, /dev/zero or /dev/stdin, may never end), up to a stated size, and a text file line by
// line up to a stated line length; SIGINT/SIGTERM stop a long read (viqu::Stopped). Every error
// is an InputError naming the file.
#include <cstdint>
#include <cstdio>
#include <string>

namespace viqu {

// The longest line a text table or trajectory may hold (bytes): a row of viqu's widest CSV
// (joints0 with torques) is under 1 KiB; a file without line breaks (a binary file, zeros) is
// refused at this length instead of read whole into one line.
constexpr size_t kMaxInputLineBytes = size_t{64} << 10;

// Throws InputError when `path` is missing, a directory, not a regular file (after following
// links; a link loop is named as such), or larger than `max_bytes`. `what` names the kind of file
// in the messages ("trajectory file"). Returns the file's size (bytes).
uintmax_t CheckInputFile(const std::string& path, uintmax_t max_bytes, const std::string& what);

// The whole file, checked as CheckInputFile does; read in chunks, so a file that grows past
// `max_bytes` while it is read is refused too.
std::string ReadInputFile(const std::string& path, uintmax_t max_bytes, const std::string& what);

// A text file line by line ('\n' ends a line; a trailing '\r' is kept for the caller), checked as
// CheckInputFile does, each line at most kMaxInputLineBytes long.
class InputLines {
 public:
  InputLines(std::string path, uintmax_t max_bytes, const std::string& what);
  ~InputLines();
  InputLines(const InputLines&) = delete;
  InputLines& operator=(const InputLines&) = delete;

  // The next line (without its '\n'); false at the end of the file.
  bool Next(std::string* line);
  int line() const { return line_; }  // 1-based number of the line last read
  const std::string& path() const { return path_; }

 private:
  bool Fill();  // reads the next chunk into buf_; false at the end of the file

  std::string path_;
  uintmax_t max_bytes_;   // the file's size bound (bytes)
  std::FILE* file_ = nullptr;
  std::string buf_;       // bytes read and not yet handed out
  size_t pos_ = 0;        // first byte of buf_ not yet handed out
  uintmax_t read_ = 0;    // bytes read so far
  bool eof_ = false;
  int line_ = 0;
};

}  // namespace viqu

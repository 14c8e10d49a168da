#pragma once
// Line-by-line reading of the text tables that datasets list their data in (EuRoC data.csv, TUM
// rgb.txt): blank lines and comment lines ('#' first) are skipped, a trailing '\r' (files written
// on Windows) is dropped, and every error names FILE:LINE.
#include <memory>
#include <string>

#include "common/input_file.h"
#include <vector>

namespace viqu::io {

// The largest table read (bytes): an hour of viqu's 1 kHz joints0 (the widest stream) is about
// 1 GiB; a bound far above any dataset's table, so that a wrong path cannot run for ever.
constexpr uintmax_t kMaxTableFileBytes = uintmax_t{4} << 30;

class TextTableReader {
 public:
  // `separator` ',' splits on commas (fields trimmed of spaces); ' ' splits on runs of spaces
  // and tabs. A missing or unreadable file, one that is no regular file or is larger than
  // kMaxTableFileBytes, and a line longer than kMaxInputLineBytes throw InputError naming it.
  TextTableReader(std::string path, char separator);

  // Reads the next data row into `fields`; false at the end of the file.
  bool Next(std::vector<std::string>* fields);

  const std::string& path() const { return path_; }
  int line() const { return line_; }  // 1-based number of the row last read
  // Throws InputError "PATH:LINE: message" for the row last read.
  [[noreturn]] void Fail(const std::string& message) const;

 private:
  std::string path_;   // as given
  char separator_;     // ',' or ' '
  std::unique_ptr<InputLines> in_;
  int line_ = 0;       // lines read so far
};

}  // namespace viqu::io

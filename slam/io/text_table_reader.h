#pragma once
// Line-by-line reading of the text tables that datasets list their data in (EuRoC data.csv, TUM
// rgb.txt): blank lines and comment lines ('#' first) are skipped, a trailing '\r' (files written
// on Windows) is dropped, and every error names FILE:LINE.
#include <fstream>
#include <string>
#include <vector>

namespace viqu::io {

class TextTableReader {
 public:
  // `separator` ',' splits on commas (fields trimmed of spaces); ' ' splits on runs of spaces
  // and tabs. A missing or unreadable file throws InputError naming it.
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
  std::ifstream in_;
  int line_ = 0;       // lines read so far
};

}  // namespace viqu::io

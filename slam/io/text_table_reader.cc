#include "slam/io/text_table_reader.h"

#include <filesystem>

#include "common/errors.h"

namespace viqu::io {
namespace {

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t");
  return s.substr(a, b - a + 1);
}

}  // namespace

TextTableReader::TextTableReader(std::string path, char separator)
    : path_(std::move(path)), separator_(separator) {
  std::error_code ec;
  if (!std::filesystem::exists(path_, ec)) throw InputError(path_ + ": file not found");
  if (std::filesystem::is_directory(path_, ec)) throw InputError(path_ + ": is a directory, not a file");
  in_.open(path_, std::ios::binary);
  if (!in_) throw InputError(path_ + ": cannot open");
}

bool TextTableReader::Next(std::vector<std::string>* fields) {
  std::string text;
  while (std::getline(in_, text)) {
    ++line_;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const std::string trimmed = Trim(text);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    fields->clear();
    if (separator_ == ',') {
      size_t start = 0;
      while (true) {
        const size_t comma = trimmed.find(',', start);
        fields->push_back(Trim(trimmed.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
    } else {
      size_t start = 0;
      while (start < trimmed.size()) {
        const size_t end = trimmed.find_first_of(" \t", start);
        fields->push_back(trimmed.substr(start, end - start));
        if (end == std::string::npos) break;
        start = trimmed.find_first_not_of(" \t", end);
      }
    }
    return true;
  }
  if (in_.bad()) throw InputError(path_ + ": read error");
  return false;
}

void TextTableReader::Fail(const std::string& message) const {
  throw InputError(path_ + ":" + std::to_string(line_) + ": " + message);
}

}  // namespace viqu::io

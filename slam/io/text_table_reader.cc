#include "slam/io/text_table_reader.h"

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
  in_ = std::make_unique<InputLines>(path_, kMaxTableFileBytes, "table file");
}

bool TextTableReader::Next(std::vector<std::string>* fields) {
  std::string text;
  while (in_->Next(&text)) {
    line_ = in_->line();
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
  return false;
}

void TextTableReader::Fail(const std::string& message) const {
  throw InputError(path_ + ":" + std::to_string(line_) + ": " + message);
}

}  // namespace viqu::io

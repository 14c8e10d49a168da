#include "common/yaml_strict.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "common/errors.h"
#include "common/input_file.h"

namespace viqu {
namespace {

// A quoted scalar ("0.6", '1') carries the non-specific tag "!": it is a string, not a number.
bool IsPlainScalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }

[[noreturn]] void FailExpected(const YamlSource& src, const YAML::Node& node,
                               const std::string& key_path, const std::string& what) {
  src.Fail(key_path, node,
           "key '" + key_path + "' expected " + what + ", got " + DescribeYamlValue(node));
}

// Parses the whole of `text` as a finite double.
bool ParseDouble(const std::string& text, double* out) {
  if (text.empty()) return false;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end != begin + text.size() || errno == ERANGE || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

// Parses the whole of `text` as a decimal integer (optional sign).
bool ParseInteger(const std::string& text, int64_t* out) {
  if (text.empty()) return false;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(begin, &end, 10);
  if (end != begin + text.size() || errno == ERANGE) return false;
  *out = static_cast<int64_t>(v);
  return true;
}

// Splits "a.b.0.c" into its components; empty components are an error (returns false).
bool SplitKeyPath(const std::string& path, std::vector<std::string>* parts) {
  parts->clear();
  size_t start = 0;
  while (true) {
    const size_t dot = path.find('.', start);
    const std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty()) return false;
    parts->push_back(part);
    if (dot == std::string::npos) return true;
    start = dot + 1;
  }
}

// A list index: only digits.
bool ParseIndex(const std::string& text, size_t* index) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  *index = static_cast<size_t>(std::stoul(text));
  return true;
}

// The largest YAML file read: scenarios and settings are a few KiB, and a sweep or a scenario
// with the most obstacles allowed stays far below this; the bound keeps a wrong path (a huge
// log, a device) from filling memory.
constexpr size_t kMaxYamlFileBytes = size_t{16} << 20;

std::string Where(const std::string& name, const YAML::Mark& mark) {
  if (mark.is_null()) return name;
  return name + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// viqu's files use no YAML tags: a tag (`!evil 2`, `!!str 2`) would be ignored by the readers or
// change how a value reads, so it is refused where it stands. "?" (plain) and "!" (quoted) are
// the non-specific tags every untagged node carries.
// `marks`: name the node's line and column after `name` (false for a --set value).
void RefuseTags(const YAML::Node& node, const std::string& name, bool marks = true) {
  const std::string& tag = node.Tag();
  if (!tag.empty() && tag != "?" && tag != "!") {
    throw InputError((marks ? Where(name, node.Mark()) : name) + ": YAML tag '" + tag + "': viqu's files use no tags");
  }
  if (node.IsMap()) {
    for (const auto& kv : node) {
      RefuseTags(kv.first, name, marks);
      RefuseTags(kv.second, name, marks);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) RefuseTags(item, name, marks);
  }
}

// The 1-based line where a second YAML document starts in `text`, or 0. A document marker is a
// line that starts with "---" or "..." followed by a space or the line's end (YAML forbids such
// lines inside a document's content, quoted or block scalars included): a "---" after content,
// or any content after "...", starts another document. A textual scan: yaml-cpp's LoadAll never
// returns on some malformed inputs (fuzz_scenario_loader found one of 339 bytes), and Load reads
// the first document only.
int SecondDocumentLine(const std::string& text) {
  bool content = false, ended = false;
  int line_no = 0;
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    const auto marker = [&](const char* m) {
      return line.compare(0, 3, m) == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t' || line[3] == '\r');
    };
    if (marker("---")) {
      if (content || ended) return line_no;
      content = line.find_first_not_of(" \t\r", 3) != std::string::npos && line[line.find_first_not_of(" \t\r", 3)] != '#';
      continue;
    }
    if (marker("...")) {
      ended = ended || content;
      continue;
    }
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#' || (line[0] == '%' && !content)) continue;
    if (ended) return line_no;
    content = true;
  }
  return 0;
}

// The one YAML document of `text` (an empty text: a null node). A second document ("---" and
// more after it) would be ignored by every reader: it is refused, named by its first line.
YAML::Node ParseText(const std::string& text, const std::string& name, bool tags_allowed) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(Where(name, e.mark) + ": YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(name + ": cannot parse YAML: " + e.what());
  }
  if (const int line = SecondDocumentLine(text)) {
    throw InputError(name + ":" + std::to_string(line) + ":1: a second YAML document (after '---'): a viqu file holds one");
  }
  if (!tags_allowed) RefuseTags(root, name);
  return root;
}

}  // namespace

std::string ReadYamlFileText(const std::string& path) {
  return ReadInputFile(path, kMaxYamlFileBytes, "scenario, settings or calibration file");
}

YAML::Node LoadYamlFile(const std::string& path) { return ParseText(ReadYamlFileText(path), path, false); }

YAML::Node LoadRunJsonFile(const std::string& path) {
  constexpr uintmax_t kMaxRunJsonBytes = uintmax_t{64} << 20;
  return ParseText(ReadInputFile(path, kMaxRunJsonBytes, "run folder's JSON file"), path, true);
}

YAML::Node LoadYamlText(const std::string& text, const std::string& name) {
  return ParseText(text, name, true);
}

void ApplyYamlOverride(YAML::Node* root, const std::string& assignment, YamlSource* src,
                       const std::string& origin) {
  const std::string where = origin.empty() ? "--set " + assignment : origin;
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos) throw InputError(where + ": expected key.path=value");
  const std::string key_path = assignment.substr(0, eq);
  std::vector<std::string> parts;
  if (!SplitKeyPath(key_path, &parts)) {
    throw InputError(where + ": '" + key_path + "' is not a key path like a.b.c");
  }
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError(where + ": the value is not valid YAML: " + e.msg);
  }
  RefuseTags(value, where, false);
  if (!root->IsDefined() || root->IsNull()) *root = YAML::Node(YAML::NodeType::Map);

  // Walk down with reset() (plain assignment between nodes would overwrite the node's content).
  YAML::Node cur;
  cur.reset(*root);
  std::string walked;
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    const std::string here = JoinKeyPath(walked, part);
    YAML::Node next;
    if (cur.IsMap()) {
      if (last) {
        cur[part] = value;
        break;
      }
      const YAML::Node& const_cur = cur;
      YAML::Node child = const_cur[part];
      if (!child.IsDefined() || child.IsNull()) cur[part] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[part]);
    } else if (cur.IsSequence()) {
      size_t index = 0;
      if (!ParseIndex(part, &index)) {
        throw InputError(where + ": '" + walked + "' is a list; '" + part + "' is not an index");
      }
      if (index >= cur.size()) {
        throw InputError(where + ": index " + part + " is out of range, '" + walked + "' has " +
                         std::to_string(cur.size()) + " elements");
      }
      if (last) {
        cur[index] = value;
        break;
      }
      next.reset(cur[index]);
    } else {
      throw InputError(where + ": '" + walked + "' is a single value, it has no key '" + part + "'");
    }
    cur.reset(next);
    walked = here;
  }
  src->AddOverride(key_path, where);
}

std::string DescribeYamlValue(const YAML::Node& node) {
  if (!node.IsDefined()) return "nothing";
  switch (node.Type()) {
    case YAML::NodeType::Null: return "nothing (null)";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Scalar: {
      std::string text = node.Scalar();
      if (text.size() > 60) text = text.substr(0, 57) + "...";
      return IsPlainScalar(node) ? "'" + text + "'" : "'\"" + text + "\"' (a quoted string)";
    }
    default: return "nothing";
  }
}

double ReadYamlNumber(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                      const NumberRange& range) {
  double v = 0;
  if (!IsPlainScalar(node) || !ParseDouble(node.Scalar(), &v) || !range.Contains(v)) {
    FailExpected(src, node, key_path, range.Describe("a number"));
  }
  return v;
}

int64_t ReadYamlInteger(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                        const NumberRange& range) {
  int64_t v = 0;
  if (!IsPlainScalar(node) || !ParseInteger(node.Scalar(), &v) ||
      !range.Contains(static_cast<double>(v))) {
    FailExpected(src, node, key_path, range.Describe("an integer"));
  }
  return v;
}

uint64_t ReadYamlUnsigned(const YamlSource& src, const YAML::Node& node, const std::string& key_path) {
  const std::string what = "an integer >= 0";
  if (!IsPlainScalar(node)) FailExpected(src, node, key_path, what);
  const std::string& text = node.Scalar();
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    FailExpected(src, node, key_path, what);
  }
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno == ERANGE) FailExpected(src, node, key_path, what + " below 2^64");
  return static_cast<uint64_t>(v);
}

bool ReadYamlBool(const YamlSource& src, const YAML::Node& node, const std::string& key_path) {
  if (IsPlainScalar(node)) {
    const std::string& t = node.Scalar();
    if (t == "true" || t == "True" || t == "TRUE") return true;
    if (t == "false" || t == "False" || t == "FALSE") return false;
  }
  FailExpected(src, node, key_path, "true or false");
}

std::string ReadYamlString(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                           bool allow_empty) {
  if (!node.IsScalar() || (!allow_empty && node.Scalar().empty())) {
    FailExpected(src, node, key_path, allow_empty ? "a string" : "a non-empty string");
  }
  return node.Scalar();
}

std::string ReadYamlChoice(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                           const std::vector<std::string>& choices) {
  std::string what = "one of ";
  for (size_t i = 0; i < choices.size(); ++i) what += (i ? ", " : "") + choices[i];
  if (node.IsScalar()) {
    for (const std::string& c : choices) {
      if (node.Scalar() == c) return c;
    }
  }
  FailExpected(src, node, key_path, what);
}

std::vector<double> ReadYamlNumberList(const YamlSource& src, const YAML::Node& node,
                                       const std::string& key_path, size_t size,
                                       const NumberRange& range, size_t min_size) {
  std::string what;
  if (size > 0) {
    what = "a list of " + std::to_string(size) + " numbers";
  } else if (min_size > 0) {
    what = "a list of at least " + std::to_string(min_size) + " numbers";
  } else {
    what = "a list of numbers";
  }
  if (!node.IsSequence() || (size > 0 && node.size() != size) || node.size() < min_size) {
    FailExpected(src, node, key_path, what);
  }
  std::vector<double> out;
  out.reserve(node.size());
  for (size_t i = 0; i < node.size(); ++i) {
    const YAML::Node& const_node = node;
    out.push_back(ReadYamlNumber(src, const_node[i], JoinKeyPath(key_path, std::to_string(i)), range));
  }
  return out;
}

}  // namespace viqu

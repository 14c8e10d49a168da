#include "common/yaml_map_reader.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "common/yaml_strict.h"

namespace viqu {

YamlMapReader::YamlMapReader(const YamlSource& src, const YAML::Node& node, std::string key_path,
                             const YAML::Node& location)
    : src_(&src), path_(std::move(key_path)), location_(location) {
  node_.reset(node);
  if (!node_.IsDefined() || node_.IsNull()) return;
  if (!node_.IsMap()) {
    src.Fail(path_, node_, (path_.empty() ? std::string("the document") : "key '" + path_ + "'") +
                               " expected a map, got " + DescribeYamlValue(node_));
  }
  for (const auto& kv : node_) {
    Entry e;
    e.key_node.reset(kv.first);
    e.value.reset(kv.second);
    if (!e.key_node.IsScalar()) {
      src.Fail(path_, e.key_node, "a key of '" + path_ + "' is not a plain name");
    }
    e.key = e.key_node.Scalar();
    if (Find(e.key) != nullptr) {
      src.Fail(KeyPath(e.key), e.key_node, "duplicate key '" + KeyPath(e.key) + "'");
    }
    entries_.push_back(std::move(e));
  }
}

const YamlMapReader::Entry* YamlMapReader::Find(const std::string& key) const {
  for (const Entry& e : entries_) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

void YamlMapReader::MarkKnown(const std::string& key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.push_back(key);
}

bool YamlMapReader::Has(const std::string& key) const { return Find(key) != nullptr; }

std::string YamlMapReader::Where(const std::string& key) const {
  const Entry* e = Find(key);
  if (e) return src_->Where(KeyPath(key), e->value);
  return src_->Where(KeyPath(key), (node_.IsDefined() && !node_.IsNull()) ? node_ : location_);
}

YAML::Node YamlMapReader::Get(const std::string& key) {
  MarkKnown(key);
  const Entry* e = Find(key);
  return e ? e->value : YAML::Node(YAML::NodeType::Undefined);
}

void YamlMapReader::Require(const std::string& key) {
  MarkKnown(key);
  if (Find(key) != nullptr) return;
  const YAML::Node& where = (node_.IsDefined() && !node_.IsNull()) ? node_ : location_;
  src_->Fail(KeyPath(key), where, "missing required key '" + KeyPath(key) + "'");
}

YamlMapReader YamlMapReader::Map(const std::string& key) {
  const YAML::Node value = Get(key);
  const Entry* e = Find(key);
  const YAML::Node& location = e ? e->key_node : ((node_.IsDefined() && !node_.IsNull()) ? node_ : location_);
  return YamlMapReader(*src_, value, KeyPath(key), location);
}

YAML::Node YamlMapReader::List(const std::string& key) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined() || value.IsNull()) return YAML::Node(YAML::NodeType::Sequence);
  if (!value.IsSequence()) {
    src_->Fail(KeyPath(key), value,
               "key '" + KeyPath(key) + "' expected a list, got " + DescribeYamlValue(value));
  }
  return value;
}

bool YamlMapReader::Number(const std::string& key, double* out, const NumberRange& range) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  *out = ReadYamlNumber(*src_, value, KeyPath(key), range);
  return true;
}

bool YamlMapReader::Integer(const std::string& key, int* out, const NumberRange& range) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  NumberRange int_range = range;
  int_range.lo = std::max(int_range.lo, static_cast<double>(std::numeric_limits<int>::min()));
  int_range.hi = std::min(int_range.hi, static_cast<double>(std::numeric_limits<int>::max()));
  *out = static_cast<int>(ReadYamlInteger(*src_, value, KeyPath(key), int_range));
  return true;
}

bool YamlMapReader::Unsigned(const std::string& key, uint64_t* out) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  *out = ReadYamlUnsigned(*src_, value, KeyPath(key));
  return true;
}

bool YamlMapReader::Bool(const std::string& key, bool* out) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  *out = ReadYamlBool(*src_, value, KeyPath(key));
  return true;
}

bool YamlMapReader::String(const std::string& key, std::string* out, bool allow_empty) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  *out = ReadYamlString(*src_, value, KeyPath(key), allow_empty);
  return true;
}

bool YamlMapReader::Choice(const std::string& key, std::string* out,
                           const std::vector<std::string>& choices) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  *out = ReadYamlChoice(*src_, value, KeyPath(key), choices);
  return true;
}

bool YamlMapReader::NumberList(const std::string& key, std::vector<double>* out, size_t size,
                               const NumberRange& range, size_t min_size) {
  const YAML::Node value = Get(key);
  if (!value.IsDefined()) return false;
  *out = ReadYamlNumberList(*src_, value, KeyPath(key), size, range, min_size);
  return true;
}

void YamlMapReader::RejectUnknownKeys() const {
  for (const Entry& e : entries_) {
    if (std::find(known_.begin(), known_.end(), e.key) != known_.end()) continue;
    std::string expected;
    for (const std::string& k : known_) expected += (expected.empty() ? "" : ", ") + k;
    src_->Fail(KeyPath(e.key), e.key_node,
               "unknown key '" + KeyPath(e.key) + "' (expected one of: " + expected + ")");
  }
}

}  // namespace viqu

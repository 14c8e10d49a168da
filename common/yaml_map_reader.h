#pragma once
#include <cstdint>
#include <cstddef>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/number_range.h"
#include "common/yaml_source.h"

namespace viqu {

// Reads one YAML map strictly: typed getters that leave the default when a key is absent and
// throw InputError (with file, line and column) on a wrong type or an out-of-range value, and
// RejectUnknownKeys(), which reports any key that no getter asked for. Duplicate keys are an
// error. Never inserts into the node.
class YamlMapReader {
 public:
  // `node` must be a map; an absent or null node reads as an empty map. `key_path` is the
  // dotted path of the map ("" for the document root). `location` is the node that messages
  // point at when keys are missing from an absent map (usually the parent map).
  YamlMapReader(const YamlSource& src, const YAML::Node& node, std::string key_path,
                const YAML::Node& location = YAML::Node());

  const YamlSource& source() const { return *src_; }
  const std::string& key_path() const { return path_; }
  // "map.key" for a key of this map.
  std::string KeyPath(const std::string& key) const { return JoinKeyPath(path_, key); }

  // True when the key is present (a null value counts as present).
  bool Has(const std::string& key) const;
  // The value of `key` (an undefined node when absent); marks the key as known.
  YAML::Node Get(const std::string& key);
  // Throws "missing required key 'a.b'" unless present; marks the key as known.
  void Require(const std::string& key);

  // A nested map (absent or null: empty).
  YamlMapReader Map(const std::string& key);
  // A list node (absent or null: an empty sequence); anything else is an error.
  YAML::Node List(const std::string& key);

  // Typed getters: when `key` is present, read it into *out and return true; when absent,
  // leave *out alone and return false.
  bool Number(const std::string& key, double* out, const NumberRange& range = NumberRange::Any());
  bool Integer(const std::string& key, int* out, const NumberRange& range = NumberRange::Any());
  bool Unsigned(const std::string& key, uint64_t* out);
  bool Bool(const std::string& key, bool* out);
  bool String(const std::string& key, std::string* out, bool allow_empty = false);
  bool Choice(const std::string& key, std::string* out, const std::vector<std::string>& choices);
  bool NumberList(const std::string& key, std::vector<double>* out, size_t size,
                  const NumberRange& range = NumberRange::Any(), size_t min_size = 0);

  // Where `key`'s value came from ("FILE:LINE:COL" or "--set ..."; the map's location when absent).
  std::string Where(const std::string& key) const;

  // Throws "unknown key 'a.b' (expected one of: ...)" for the first key that no getter asked for.
  void RejectUnknownKeys() const;

 private:
  struct Entry {
    std::string key;     // key text
    YAML::Node key_node; // the key itself (its mark locates unknown keys)
    YAML::Node value;    // the value
  };
  const Entry* Find(const std::string& key) const;
  void MarkKnown(const std::string& key);

  const YamlSource* src_;           // not owned; outlives the reader
  std::string path_;                // dotted path of this map
  YAML::Node node_;                 // the map, or undefined/null when absent
  YAML::Node location_;             // where messages about an absent map point
  std::vector<Entry> entries_;      // the map's entries in document order
  std::vector<std::string> known_;  // keys a getter asked for, in order of asking
};

}  // namespace viqu

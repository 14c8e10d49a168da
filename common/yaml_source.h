#pragma once
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace viqu {

// Where the nodes of one YAML document came from: the file, plus the command-line overrides
// (`--set key.path=value`) applied to it. Turns a key path and a node into the location that
// an error message starts with: "FILE:LINE:COL" (1-based) for nodes read from the file, or
// "--set key.path=value" for keys an override wrote.
class YamlSource {
 public:
  explicit YamlSource(std::string file);

  const std::string& file() const { return file_; }

  // Records that an override wrote the subtree at `key_path` ("a.b"); `where` is what messages
  // about it start with ("--set a.b=value", or the file and line it was read from).
  void AddOverride(const std::string& key_path, const std::string& where);

  // The location of `node`, read as key `key_path` (dotted, list elements by index:
  // "obstacles.0.speed_mps"). A key written or created by an override reports the override.
  std::string Where(const std::string& key_path, const YAML::Node& node) const;

  // Throws InputError("WHERE: message").
  [[noreturn]] void Fail(const std::string& key_path, const YAML::Node& node,
                         const std::string& message) const;

 private:
  std::string file_;  // path as the user gave it
  std::vector<std::pair<std::string, std::string>> overrides_;  // (key path, where), in order
};

// "parent.key", or "key" when parent is empty.
std::string JoinKeyPath(const std::string& parent, const std::string& key);

}  // namespace viqu

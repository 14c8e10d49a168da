#pragma once
// Strict YAML reading on top of yaml-cpp: every error is an InputError whose message starts
// with "FILE:LINE:COL" (1-based) and says which key was wrong, what was expected and what was
// found. Scenario files and the SLAM settings share these helpers.
//
//   YamlSource src(path);
//   YAML::Node root = LoadYamlFile(path);
//   for (const auto& s : overrides) ApplyYamlOverride(&root, s, &src);
//   YamlMapReader top(src, root, "");
//   top.Number("duration_s", &duration_s, NumberRange::Positive());
//   top.RejectUnknownKeys();
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/number_range.h"
#include "common/yaml_map_reader.h"
#include "common/yaml_source.h"

namespace viqu {

// Reads and parses a YAML file of viqu's own (scenario, settings, sweep). Missing or unreadable
// file: InputError naming it; syntax error: InputError "FILE:LINE:COL: YAML syntax error: ...";
// a second document ("---") or a tag ("!x", "!!str") is refused at FILE:LINE:COL. An empty file
// gives a null node.
YAML::Node LoadYamlFile(const std::string& path);

// The text of a YAML file: a regular file (not a device or pipe) of at most 16 MiB; InputError
// naming the file otherwise. LoadYamlFile parses it; readers of YAML dialects adjust it first.
std::string ReadYamlFileText(const std::string& path);

// A JSON file of a run folder (its marker, metrics.json), read as any input: a regular file of at
// most 64 MiB (a marker listing a long recording's images is a few MiB), parsed as YAML.
YAML::Node LoadRunJsonFile(const std::string& path);

// Parses YAML text of another program's dialect (OpenCV's, with tags such as !!opencv-matrix);
// `name` stands for the file in messages. A second document is refused as above.
YAML::Node LoadYamlText(const std::string& text, const std::string& name);

// Applies one override "key.path=value" to `root` (a map): the value is parsed as YAML (so
// "[]", "10", "{a: 1}" work), map keys along the path are created when missing, list
// elements are addressed by index ("obstacles.0.speed_mps"). Records the override in `src`
// so that errors about keys it wrote name it: `origin` when given (e.g. "scenario.yaml:28:5",
// for an override that a scenario's key made), else "--set key.path=value". Malformed overrides
// throw InputError.
void ApplyYamlOverride(YAML::Node* root, const std::string& assignment, YamlSource* src,
                       const std::string& origin = "");

// How a node looks in a message: "'abc'" for a scalar, "a list", "a map", "nothing".
std::string DescribeYamlValue(const YAML::Node& node);

// Typed reading of one scalar node, read as key `key_path`. Wrong type or out-of-range value:
// InputError "WHERE: key 'a.b' expected <what>, got <value>".
double ReadYamlNumber(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                      const NumberRange& range = NumberRange::Any());
int64_t ReadYamlInteger(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                        const NumberRange& range = NumberRange::Any());
uint64_t ReadYamlUnsigned(const YamlSource& src, const YAML::Node& node, const std::string& key_path);
bool ReadYamlBool(const YamlSource& src, const YAML::Node& node, const std::string& key_path);
// Any scalar that is not null; `allow_empty` = false rejects "".
std::string ReadYamlString(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                           bool allow_empty = false);
// A string from a fixed set.
std::string ReadYamlChoice(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
                           const std::vector<std::string>& choices);
// A list of numbers; `size` > 0 demands exactly that many, 0 accepts any length (>= min_size).
std::vector<double> ReadYamlNumberList(const YamlSource& src, const YAML::Node& node,
                                       const std::string& key_path, size_t size,
                                       const NumberRange& range = NumberRange::Any(), size_t min_size = 0);

}  // namespace viqu

#pragma once
// Writing settings back as YAML (the resolved scenario, the resolved SLAM settings): one key and
// value at a time into a yaml-cpp emitter, numbers in the shortest form that reads back as the
// same double, so that a written file loads to identical values.
#include <string>

#include <yaml-cpp/yaml.h>

namespace viqu {

// The shortest of %.15g / %.17g that reads back as the same double.
std::string YamlNumberText(double v);

void EmitNumber(YAML::Emitter& out, const std::string& key, double value);
void EmitInt(YAML::Emitter& out, const std::string& key, long long value);
void EmitBool(YAML::Emitter& out, const std::string& key, bool value);
// A free string, double-quoted.
void EmitString(YAML::Emitter& out, const std::string& key, const std::string& value);
// A value from a fixed set of plain words (trot, stereo, ...): no quotes needed.
void EmitWord(YAML::Emitter& out, const std::string& key, const std::string& value);

}  // namespace viqu

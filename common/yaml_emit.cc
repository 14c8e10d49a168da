#include "common/yaml_emit.h"

#include <cstdio>
#include <cstdlib>

namespace viqu {

std::string YamlNumberText(double v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.15g", v);
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

void EmitNumber(YAML::Emitter& out, const std::string& key, double value) {
  out << YAML::Key << key << YAML::Value << YamlNumberText(value);
}

void EmitInt(YAML::Emitter& out, const std::string& key, long long value) {
  out << YAML::Key << key << YAML::Value << std::to_string(value);
}

void EmitBool(YAML::Emitter& out, const std::string& key, bool value) {
  out << YAML::Key << key << YAML::Value << (value ? "true" : "false");
}

void EmitString(YAML::Emitter& out, const std::string& key, const std::string& value) {
  out << YAML::Key << key << YAML::Value << YAML::DoubleQuoted << value;
}

void EmitWord(YAML::Emitter& out, const std::string& key, const std::string& value) {
  out << YAML::Key << key << YAML::Value << value;
}

}  // namespace viqu

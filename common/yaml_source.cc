#include "common/yaml_source.h"

#include "common/errors.h"

namespace viqu {
namespace {

// True when `prefix` equals `path` or names one of its ancestors ("a.b" for "a.b.c").
bool IsPathPrefix(const std::string& prefix, const std::string& path) {
  if (path.size() < prefix.size() || path.compare(0, prefix.size(), prefix) != 0) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.';
}

}  // namespace

YamlSource::YamlSource(std::string file) : file_(std::move(file)) {}

void YamlSource::AddOverride(const std::string& key_path, const std::string& where) {
  overrides_.emplace_back(key_path, where);
}

std::string YamlSource::Where(const std::string& key_path, const YAML::Node& node) const {
  // The latest override that wrote this key (or one of its ancestors), or that created it on
  // the way to a deeper key, is where the value came from.
  for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
    if (IsPathPrefix(it->first, key_path) || IsPathPrefix(key_path, it->first)) {
      return it->second;
    }
  }
  if (node.IsDefined()) {
    const YAML::Mark mark = node.Mark();
    if (!mark.is_null()) {
      return file_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
    }
  }
  return file_;
}

void YamlSource::Fail(const std::string& key_path, const YAML::Node& node,
                      const std::string& message) const {
  throw InputError(Where(key_path, node) + ": " + message);
}

std::string JoinKeyPath(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

}  // namespace viqu

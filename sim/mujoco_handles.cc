#include "sim/mujoco_handles.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <regex>

#include <unistd.h>

#include "common/errors.h"

namespace viqu::sim {
namespace {

std::mutex g_warn_mutex;
std::vector<std::string> g_warnings;

void ThrowingError(const char* msg) { throw RunError(std::string("MuJoCo error: ") + msg); }

void CollectWarning(const char* msg) {
  std::lock_guard<std::mutex> lock(g_warn_mutex);
  g_warnings.emplace_back(msg);
}

// mj_loadXML resolves every file attribute relative to the folder of the main file and has no
// notion of absolute paths. We write composed scenes to a temporary folder, so absolute paths
// are rewritten as "../" up to the file-system root followed by the path.
std::string RootRelativeXml(const std::string& xml, const std::string& dir) {
  int depth = 0;
  for (char c : dir) depth += (c == '/');
  std::string up;
  for (int i = 0; i < depth; ++i) up += "../";
  static const std::regex kAbsFile(R"re(file="/)re");
  return std::regex_replace(xml, kAbsFile, "file=\"" + up);
}

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = ThrowingError;
    mju_user_warning = CollectWarning;
  });
}

std::vector<std::string> TakeMujocoWarnings() {
  std::lock_guard<std::mutex> lock(g_warn_mutex);
  std::vector<std::string> out;
  out.swap(g_warnings);
  return out;
}

ModelPtr LoadModelFile(const std::string& path) {
  InstallMujocoHandlers();
  char err[1024] = "";
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, err, sizeof(err)));
  if (!m) throw InputError(path + ": cannot load MuJoCo model: " + err);
  return m;
}

ModelPtr LoadModelString(const std::string& xml, const std::string& what,
                         const std::function<std::string(int)>& source_of_line) {
  InstallMujocoHandlers();
  char dir_template[] = "/tmp/viqu-scene-XXXXXX";
  const char* dir = ::mkdtemp(dir_template);
  if (!dir) throw RunError("cannot create a temporary folder for " + what);
  const std::string dir_s = std::string(dir) + "/";
  const std::string file = dir_s + "scene.xml";
  {
    std::ofstream out(file);
    out << RootRelativeXml(xml, dir_s);
  }
  char err[1024] = "";
  ModelPtr m(mj_loadXML(file.c_str(), nullptr, err, sizeof(err)));
  std::remove(file.c_str());
  ::rmdir(dir);
  if (!m) {
    static const std::regex kLine(", line ([0-9]+)");
    std::string message = err;
    std::smatch at;
    const std::string source =
        source_of_line && std::regex_search(message, at, kLine) ? source_of_line(std::stoi(at[1])) : "";
    if (source.empty()) throw InputError(what + ": cannot load composed MuJoCo model: " + message);
    message = std::regex_replace(message, kLine, "");
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    throw InputError(source + ": cannot load MuJoCo model: " + message + " (the scene of " + what + ")");
  }
  return m;
}

std::string MjName(const mjModel* m, mjtObj type, int id) {
  const char* n = mj_id2name(m, type, id);
  return n ? std::string(n) : std::string();
}

int MjIdOrThrow(const mjModel* m, mjtObj type, const std::string& name, const std::string& what) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw InputError(what + ": model has no object named '" + name + "'");
  return id;
}

}  // namespace viqu::sim

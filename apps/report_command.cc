#include "apps/report_command.h"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <filesystem>

#include "common/errors.h"

extern char** environ;

namespace viqu::app {
namespace {

// Debian's interpreter, where python3-matplotlib is installed (scripts/setup.sh): a python3
// earlier on PATH (pyenv, a virtualenv) may lack it.
constexpr const char* kPython = "/usr/bin/python3";

}  // namespace

int RunReport(const std::string& dir, const std::vector<std::string>& args) {
  const std::string tool = std::string(VIQU_TOOLS_DIR) + "/report.py";
  std::error_code ec;
  if (!std::filesystem::exists(kPython, ec)) throw RunError(std::string(kPython) + " not found (scripts/setup.sh installs it)");
  if (!std::filesystem::exists(tool, ec)) throw RunError(tool + " not found");
  std::vector<std::string> all = {kPython, tool, dir};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (posix_spawn(&pid, kPython, nullptr, nullptr, argv.data(), environ) != 0) throw RunError("cannot start " + tool);
  int status = 0;
  pid_t got;
  while ((got = ::waitpid(pid, &status, 0)) == -1 && errno == EINTR) {
  }  // a stop signal reaches the tool too (same process group); wait for it to end
  if (got != pid) throw RunError("lost the report process");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace viqu::app

#include "apps/report_command.h"

#include <filesystem>

#include "common/child_process.h"
#include "common/errors.h"

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
  return WaitProcess(StartProcess(all));
}

}  // namespace viqu::app

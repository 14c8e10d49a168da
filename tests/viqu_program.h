#pragma once
// Runs the built `viqu` program from tests: to completion (RunViqu) or in the background, to be
// signalled (SpawnViqu). Header-only, shared by the tests that drive the command line.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/child_process.h"

namespace viqu::testing {

inline std::string ViquBinary() { return std::string(VIQU_BINARY_DIR) + "/apps/viqu"; }
inline bool ViquBuilt() { return std::filesystem::exists(ViquBinary()); }

struct ProgramResult {
  int exit_code = -1;  // exit status; 128 + N when killed by signal N
  std::string output;  // stdout and stderr together
};

// Runs `viqu ARGS` through the shell (ARGS is shell text) and waits for it.
inline ProgramResult RunViqu(const std::string& args) {
  ProgramResult r;
  const std::string cmd = ViquBinary() + " " + args + " 2>&1";
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[512];
  for (size_t n; (n = std::fread(buf, 1, sizeof(buf), p)) > 0;) r.output.append(buf, n);
  r.exit_code = ExitCodeOf(::pclose(p));
  return r;
}

// Starts `viqu ARGS...` with stdout and stderr into `log_path`; returns its PID.
inline pid_t SpawnViqu(const std::vector<std::string>& args, const std::string& log_path) {
  std::vector<std::string> all = {ViquBinary()};
  all.insert(all.end(), args.begin(), args.end());
  return StartProcess(all, log_path);
}

// Waits for a spawned process; its exit code as RunViqu reports it.
inline int WaitViqu(pid_t pid) { return WaitProcess(pid); }

}  // namespace viqu::testing

#pragma once
// Runs the built `viqu` program from tests: to completion (RunViqu) or in the background, to be
// signalled (SpawnViqu). Header-only, shared by the tests that drive the command line.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace viqu::testing {

inline std::string ViquBinary() { return std::string(VIQU_BINARY_DIR) + "/apps/viqu"; }
inline bool ViquBuilt() { return std::filesystem::exists(ViquBinary()); }

struct ProgramResult {
  int exit_code = -1;  // exit status; 128 + N when killed by signal N
  std::string output;  // stdout and stderr together
};

inline int DecodeStatus(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

// Runs `viqu ARGS` through the shell (ARGS is shell text) and waits for it.
inline ProgramResult RunViqu(const std::string& args) {
  ProgramResult r;
  const std::string cmd = ViquBinary() + " " + args + " 2>&1";
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[512];
  for (size_t n; (n = std::fread(buf, 1, sizeof(buf), p)) > 0;) r.output.append(buf, n);
  r.exit_code = DecodeStatus(::pclose(p));
  return r;
}

// Starts `viqu ARGS...` with stdout and stderr into `log_path`; returns its PID (or -1).
inline pid_t SpawnViqu(const std::vector<std::string>& args, const std::string& log_path) {
  std::vector<std::string> all = {ViquBinary()};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Waits for a spawned process; its exit code as RunViqu reports it.
inline int WaitViqu(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return DecodeStatus(status);
}

}  // namespace viqu::testing

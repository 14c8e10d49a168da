#pragma once
// Starting and waiting for child processes (sweep points, the report tool, tests of the program).
#include <sys/types.h>

#include <string>
#include <vector>

namespace viqu {

// Starts argv[0] (a path) with `argv`, stdin from /dev/null and, when `log_path` is not empty,
// stdout and stderr into that file (truncated). Returns the PID; RunError when it cannot start.
pid_t StartProcess(const std::vector<std::string>& argv, const std::string& log_path = "");

// A finished child's exit code as a shell reports it: its exit status, or 128 + the signal that
// ended it.
int ExitCodeOf(int wait_status);

// Waits for the child `pid` (through interrupted waits) and returns ExitCodeOf its status.
// RunError when `pid` is not a child of this process.
int WaitProcess(pid_t pid);

}  // namespace viqu

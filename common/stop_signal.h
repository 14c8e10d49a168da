#pragma once

namespace viqu {

// SIGINT and SIGTERM ask a run to stop at the next frame boundary: the run loop polls
// StopSignal(), finishes its outputs, marks the folder incomplete and exits with 128 + signal.
// The first signal restores the default action, so a second one kills at once.
void InstallStopSignalHandlers();
// 0 while no stop was asked, else the signal number.
int StopSignal();
// Exit code for a run stopped by `signal` (130 for SIGINT, 143 for SIGTERM).
inline int ExitCodeForSignal(int signal) { return 128 + signal; }
// "SIGINT", "SIGTERM" or "signal N".
const char* SignalName(int signal);

}  // namespace viqu

#pragma once
#include <string>

#include "apps/cli.h"

namespace viqu::app {

// `viqu view`: runs the scenario as `viqu run` does, shown in a window (viewer/run_viewer.h).
// Returns the run's exit code; without a display, 1 (the run folder is not written); in a build
// without GLFW, 2 with a message saying so.
int RunViewCommand(const ViewArgs& args, const std::string& command_line);

}  // namespace viqu::app

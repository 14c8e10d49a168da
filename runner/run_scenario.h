#pragma once
#include "runner/run_options.h"
#include "scenario/scenario.h"

namespace viqu::runner {

// `viqu run`: simulates the scenario, produces the sensor streams, writes the run folder
// (DESIGN.md) and prints a summary. Returns the process exit code: 0, or 1 when the robot fell
// and the scenario does not allow it. Throws InputError / RunError.
int RunScenario(const Scenario& s, const RunOptions& opt);

}  // namespace viqu::runner

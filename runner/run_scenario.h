#pragma once
#include "runner/run_observer.h"
#include "runner/run_options.h"
#include "scenario/scenario.h"

namespace viqu::runner {

// `viqu run`: simulates the scenario, produces the sensor streams, writes the run folder
// (DESIGN.md) and prints a summary. Returns the process exit code: 0, or 1 when the robot fell
// and the scenario does not allow it. Throws InputError / RunError. `observer` (not owned; may be
// null) sees every camera frame (run_observer.h); with one, the estimator stage runs inline.
int RunScenario(const Scenario& s, const RunOptions& opt, RunObserver* observer = nullptr);

}  // namespace viqu::runner

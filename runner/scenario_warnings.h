#pragma once
// What in a valid scenario is likely not what its author meant: each is printed as
// "viqu: warning: ..." before the run starts, and the run goes on (the keys are well-formed and
// in range, so refusing them would stop runs that mean it, e.g. a scenario shortened with --set
// duration_s).
#include <optional>
#include <string>
#include <vector>

#include "scenario/scenario.h"
#include "sim/terrain.h"

namespace viqu::runner {

// `dynamic_method`: the method of the dynamic-object stage the SLAM settings run, "" when it does
// not run (mode visual, method none, or no SLAM); `floor`: the world's floor, when it is bounded.
std::vector<std::string> ScenarioWarnings(const Scenario& s, const std::string& dynamic_method,
                                          const std::optional<sim::FloorExtent>& floor);

}  // namespace viqu::runner

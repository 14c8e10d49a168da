#pragma once
// The SLAM settings a scenario runs with: its settings file (slam.config, or the default) with the
// scenario's slam.mode / slam.dynamic.* / slam.lo.* / slam.stereo.* keys on top, checked against
// its camera's image size. `viqu run` and a sweep's check of its points before anything runs
// read them the same way.
#include "scenario/scenario.h"
#include "slam/settings/slam_settings.h"

namespace viqu::runner {

// Throws InputError naming the file and line (or the --set) of the value it refuses.
slam::SlamSettings ScenarioSlamSettings(const Scenario& s);

}  // namespace viqu::runner

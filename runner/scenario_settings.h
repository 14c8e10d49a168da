#pragma once
// The SLAM settings a scenario runs with: its settings file (slam.config, or the default) with the
// scenario's slam.mode / slam.dynamic.* / slam.lo.* / slam.stereo.* keys on top, checked against
// its camera's image size. `viqu run` and a sweep's check of its points before anything runs
// read them the same way.
#include <string>
#include <vector>

#include "scenario/scenario.h"
#include "slam/settings/slam_settings.h"

namespace viqu::runner {

// What the settings are made from: the file, the overrides in order (the scenario's IMU sampling
// first) with where each was written, and the image size the pyramid is checked against.
struct ScenarioSettingsInputs {
  std::string path;
  std::vector<std::string> overrides, origins;
  int width = 0, height = 0;
  std::string size_where;  // where the scenario set the image size (empty: its defaults)
  // The inputs as one string: equal for two scenarios exactly when their settings are equal
  // (origins aside), so a caller can load each distinct one once.
  std::string Key() const;
};
ScenarioSettingsInputs SettingsInputsOf(const Scenario& s);

// Throws InputError naming the file and line (or the --set) of the value it refuses.
slam::SlamSettings LoadScenarioSettings(const ScenarioSettingsInputs& in);
inline slam::SlamSettings ScenarioSlamSettings(const Scenario& s) { return LoadScenarioSettings(SettingsInputsOf(s)); }

}  // namespace viqu::runner

#include "runner/scenario_settings.h"

#include <string>
#include <vector>

#include "common/errors.h"

namespace viqu::runner {

ScenarioSettingsInputs SettingsInputsOf(const Scenario& s) {
  ScenarioSettingsInputs in;
  in.path = s.slam.config.empty() ? slam::DefaultSlamSettingsPath() : s.slam.config;
  // The estimator integrates the IMU as the scenario's IMU samples it, unless slam.lo says
  // otherwise (its overrides come after).
  in.overrides = {"lo.imu_sampling=" + s.sensors.imu.sampling};
  in.overrides.insert(in.overrides.end(), s.slam.settings_overrides.begin(), s.slam.settings_overrides.end());
  in.origins = {s.source_file + " (sensors.imu.sampling)"};
  in.origins.insert(in.origins.end(), s.slam.settings_override_origins.begin(), s.slam.settings_override_origins.end());
  in.width = s.sensors.camera.width;
  in.height = s.sensors.camera.height;
  in.size_where = s.sensors.camera.size_where;
  return in;
}

std::string ScenarioSettingsInputs::Key() const {
  std::string key = path + "\n" + std::to_string(width) + "x" + std::to_string(height);
  for (const std::string& o : overrides) key += "\n" + o;
  return key;
}

slam::SlamSettings LoadScenarioSettings(const ScenarioSettingsInputs& in) {
  slam::SlamSettings settings = slam::LoadSlamSettings(in.path, in.overrides, in.origins);
  const std::string pyramid = slam::PyramidProblem(settings.orb.scale_factor, settings.orb.num_levels, in.width, in.height);
  if (pyramid.empty()) return settings;
  // The value the user chose is blamed: the scenario's image size, unless the pyramid's keys
  // were set elsewhere than in the default settings (a 16x16 camera was refused naming
  // default.yaml's orb.num_levels line).
  const bool pyramid_default = settings.pyramid_where.rfind(slam::DefaultSlamSettingsPath(), 0) == 0;
  if (pyramid_default && !in.size_where.empty()) {
    throw InputError(in.size_where + ": the " + std::to_string(in.width) + "x" + std::to_string(in.height) +
                     " camera image is too small for the SLAM settings' ORB pyramid (" + settings.pyramid_where + "): " +
                     pyramid);
  }
  throw InputError(settings.pyramid_where + ": " + pyramid);
  return settings;
}

}  // namespace viqu::runner

#include "runner/scenario_settings.h"

#include <string>
#include <vector>

#include "common/errors.h"

namespace viqu::runner {

slam::SlamSettings ScenarioSlamSettings(const Scenario& s) {
  const std::string path = s.slam.config.empty() ? slam::DefaultSlamSettingsPath() : s.slam.config;
  // The estimator integrates the IMU as the scenario's IMU samples it, unless slam.lo says
  // otherwise (its overrides come after).
  std::vector<std::string> overrides{"lo.imu_sampling=" + s.sensors.imu.sampling};
  overrides.insert(overrides.end(), s.slam.settings_overrides.begin(), s.slam.settings_overrides.end());
  std::vector<std::string> origins{s.source_file + " (sensors.imu.sampling)"};
  origins.insert(origins.end(), s.slam.settings_override_origins.begin(), s.slam.settings_override_origins.end());
  slam::SlamSettings settings = slam::LoadSlamSettings(path, overrides, origins);
  const std::string pyramid = slam::PyramidProblem(settings.orb.scale_factor, settings.orb.num_levels,
                                                   s.sensors.camera.width, s.sensors.camera.height);
  if (!pyramid.empty()) throw InputError(settings.pyramid_where + ": " + pyramid);
  return settings;
}

}  // namespace viqu::runner

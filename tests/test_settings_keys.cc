// The scenario's slam.lo keys mirror the SLAM settings' lo.* keys. The scenario loader cannot
// depend on the SLAM library, so it lists those keys itself (scenario_loader.cc); this test
// links both and checks that every lo.* setting the SLAM settings write can be set from a
// scenario and reaches the SLAM settings, so that a key added to one and not the other fails
// here instead of in a user's sweep.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "scenario/scenario_loader.h"
#include "slam/settings/slam_settings.h"

namespace viqu {
namespace {

TEST(SettingsKeys, EveryLegOdometrySettingCanBeSetFromAScenario) {
  const slam::SlamSettings defaults = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath());
  const YAML::Node lo = YAML::Load(slam::SlamSettingsToYaml(defaults))["lo"];
  ASSERT_TRUE(lo && lo.IsMap());
  const std::string scenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
  int keys = 0;
  for (const auto& kv : lo) {
    const std::string key = kv.first.as<std::string>();
    const std::string value = kv.second.as<std::string>();
    SCOPED_TRACE("slam.lo." + key);
    Scenario s;
    ASSERT_NO_THROW(s = LoadScenario(scenario, {"slam.lo." + key + "=" + value}));
    // The scenario passes it on as a SLAM settings override, which the settings accept.
    bool passed_on = false;
    for (const std::string& o : s.slam.settings_overrides) passed_on = passed_on || o.rfind("lo." + key + "=", 0) == 0;
    EXPECT_TRUE(passed_on);
    EXPECT_NO_THROW(slam::LoadSlamSettings(slam::DefaultSlamSettingsPath(), s.slam.settings_overrides));
    ++keys;
  }
  EXPECT_GE(keys, 26);  // 26 lo keys when written
}

}  // namespace
}  // namespace viqu

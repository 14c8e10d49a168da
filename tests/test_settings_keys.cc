// The scenario's slam.lo, slam.dynamic and slam.stereo keys mirror the SLAM settings' lo.*, dynamic.*
// and stereo.* keys.
// The scenario loader cannot depend on the SLAM library, so it lists those keys itself
// (scenario_loader.cc); this test links both and checks that every such setting the SLAM
// settings write can be set from a scenario, reaches the SLAM settings and is written back into
// the run folder's scenario.yaml, so that a key added to one and not the other fails here instead
// of in a user's sweep.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "scenario/scenario_loader.h"
#include "slam/settings/slam_settings.h"

namespace viqu {
namespace {

// Sets each key of the SLAM settings' block `block` (a flat map: lo, stereo) from a scenario as
// `slam.<block>.<key>` at its default value, and checks that the scenario passes it on as a
// settings override the settings accept and writes it back into scenario.yaml. Returns the
// number of keys.
int ExpectEveryKeySettableFromAScenario(const std::string& block) {
  const slam::SlamSettings defaults = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath());
  const YAML::Node map = YAML::Load(slam::SlamSettingsToYaml(defaults))[block];
  EXPECT_TRUE(map && map.IsMap());
  if (!map || !map.IsMap()) return 0;
  const std::string scenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
  int keys = 0;
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    const std::string value = kv.second.as<std::string>();
    SCOPED_TRACE("slam." + block + "." + key);
    Scenario s;
    try {
      s = LoadScenario(scenario, {"slam." + block + "." + key + "=" + value});
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    bool passed_on = false;
    for (const std::string& o : s.slam.settings_overrides) passed_on = passed_on || o.rfind(block + "." + key + "=", 0) == 0;
    EXPECT_TRUE(passed_on);
    EXPECT_NO_THROW(slam::LoadSlamSettings(slam::DefaultSlamSettingsPath(), s.slam.settings_overrides));
    const YAML::Node written = YAML::Load(ScenarioToYaml(s))["slam"][block][key];
    EXPECT_TRUE(written && written.IsScalar());
    if (written && written.IsScalar()) {
      double number = 0;
      if (YAML::convert<double>::decode(kv.second, number)) {
        EXPECT_DOUBLE_EQ(written.as<double>(), number);
      } else {
        EXPECT_EQ(written.as<std::string>(), value);
      }
    }
    ++keys;
  }
  return keys;
}

TEST(SettingsKeys, EveryLegOdometrySettingCanBeSetFromAScenario) {
  EXPECT_GE(ExpectEveryKeySettableFromAScenario("lo"), 26);  // 26 lo keys when written
}

TEST(SettingsKeys, EveryStereoSettingCanBeSetFromAScenario) {
  EXPECT_GE(ExpectEveryKeySettableFromAScenario("stereo"), 17);  // 17 stereo keys when written
}

// The leaves of a YAML map as (dotted path, value).
void Leaves(const YAML::Node& node, const std::string& prefix, std::vector<std::pair<std::string, std::string>>* out) {
  for (const auto& kv : node) {
    const std::string path = prefix + kv.first.as<std::string>();
    if (kv.second.IsMap()) {
      Leaves(kv.second, path + ".", out);
    } else {
      out->emplace_back(path, kv.second.as<std::string>());
    }
  }
}

TEST(SettingsKeys, EveryDynamicObjectSettingCanBeSetFromAScenario) {
  const slam::SlamSettings defaults = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath());
  const YAML::Node dynamic = YAML::Load(slam::SlamSettingsToYaml(defaults))["dynamic"];
  ASSERT_TRUE(dynamic && dynamic.IsMap());
  std::vector<std::pair<std::string, std::string>> leaves;
  Leaves(dynamic, "", &leaves);
  const std::string scenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
  for (const auto& [key, value] : leaves) {
    SCOPED_TRACE("slam.dynamic." + key);
    Scenario s;
    ASSERT_NO_THROW(s = LoadScenario(scenario, {"slam.dynamic." + key + "=" + value}));
    bool passed_on = false;
    for (const std::string& o : s.slam.settings_overrides) passed_on = passed_on || o == "dynamic." + key + "=" + value;
    EXPECT_TRUE(passed_on);
    EXPECT_NO_THROW(slam::LoadSlamSettings(slam::DefaultSlamSettingsPath(), s.slam.settings_overrides));
    // Written back where it was read from.
    const YAML::Node written = YAML::Load(ScenarioToYaml(s))["slam"]["dynamic"];
    YAML::Node at = YAML::Clone(written);
    size_t begin = 0;
    for (size_t dot = key.find('.'); ; dot = key.find('.', begin)) {
      at = at[key.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin)];
      if (dot == std::string::npos) break;
      begin = dot + 1;
    }
    ASSERT_TRUE(at.IsScalar());
    if (key == "method" || value == "true" || value == "false") {
      EXPECT_EQ(at.as<std::string>(), value);
    } else {
      EXPECT_DOUBLE_EQ(at.as<double>(), std::stod(value));
    }
  }
  EXPECT_GE(leaves.size(), 27u);  // 27 dynamic keys when written (method, 7 of eq. 1-4, forget_s,
                                  // keep_past_observations, 3 priors, 15 adaptive)
}

TEST(SettingsKeys, AScenariosStereoKeyChangesTheSettings) {
  const std::string scenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
  const Scenario s = LoadScenario(scenario, {"slam.stereo.near_mono_baselines=0", "slam.stereo.max_hamming=60"});
  const slam::SlamSettings settings = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath(), s.slam.settings_overrides);
  EXPECT_EQ(settings.stereo.near_mono_baselines, 0);
  EXPECT_EQ(settings.stereo.max_hamming, 60);
  const slam::SlamSettings defaults = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath());
  EXPECT_GT(defaults.stereo.near_mono_baselines, 0);
  EXPECT_NE(defaults.stereo.max_hamming, 60);
  // Out of range is the SLAM settings' error, naming the key.
  const Scenario bad = LoadScenario(scenario, {"slam.stereo.near_right_weight_ba=2"});
  try {
    slam::LoadSlamSettings(slam::DefaultSlamSettingsPath(), bad.slam.settings_overrides);
    FAIL() << "a weight of 2 was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("near_right_weight_ba"), std::string::npos) << e.what();
  }
}

TEST(SettingsKeys, AMisspeltAdaptiveKeyIsAnErrorAtItsLine) {
  const std::string scenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
  try {
    LoadScenario(scenario, {"slam.dynamic.adaptive.treshold_m=0.01"});
    FAIL() << "a misspelt key was accepted";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("treshold_m"), std::string::npos) << what;
    EXPECT_NE(what.find("threshold_m"), std::string::npos) << what;  // the keys it expected
  }
}

}  // namespace
}  // namespace viqu

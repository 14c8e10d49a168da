// Strict scenario loading: defaults, file:line:column errors, --set overrides, round trip.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "common/yaml_strict.h"
#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

class ConfigLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "viqu_cfg_XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
    Write("world.xml", "<mujoco/>\n");
    Write("rat.xml", "<mujoco/>\n");
    Write("rat.urdf", "<robot name='rat'/>\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }

  // The InputError message of loading `yaml` (written as scen.yaml) with `overrides`, or a
  // failure marker when no InputError is thrown.
  std::string ErrorOf(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
    const std::string path = Write("scen.yaml", yaml);
    try {
      LoadScenario(path, overrides);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no InputError>";
  }

  std::string ScenPath() const { return (dir_ / "scen.yaml").string(); }

  fs::path dir_;
};

const char* const kMinimal =
    "name: mini\n"
    "world: world.xml\n"
    "robot:\n"
    "  model: rat.xml\n";

TEST_F(ConfigLoaderTest, MinimalScenarioLoadsWithDefaults) {
  const Scenario s = LoadScenario(Write("scen.yaml", kMinimal));
  const Scenario d;
  EXPECT_EQ(s.name, "mini");
  EXPECT_EQ(s.source_file, (dir_ / "scen.yaml").string());
  EXPECT_EQ(s.world, (dir_ / "world.xml").string());
  EXPECT_EQ(s.robot.model, (dir_ / "rat.xml").string());
  EXPECT_EQ(s.seed, d.seed);
  EXPECT_DOUBLE_EQ(s.duration_s, d.duration_s);
  EXPECT_DOUBLE_EQ(s.physics_dt_s, d.physics_dt_s);
  EXPECT_EQ(s.robot.gait.type, "trot");
  EXPECT_DOUBLE_EQ(s.robot.gait.duty, d.robot.gait.duty);
  EXPECT_DOUBLE_EQ(s.sensors.camera.rate_hz, d.sensors.camera.rate_hz);
  EXPECT_EQ(s.sensors.camera.width, 640);
  EXPECT_TRUE(s.sensors.camera.depth);
  EXPECT_DOUBLE_EQ(s.sensors.imu.rate_hz, d.sensors.imu.rate_hz);
  // A good detector by default (sim/segmentation_model.h).
  EXPECT_EQ(s.sensors.segmentation.min_area_px, 150);
  EXPECT_EQ(s.sensors.segmentation.false_positive_rate, 0.0);
  EXPECT_EQ(s.sensors.segmentation.wrong_category_rate, 0.0);
  EXPECT_EQ(s.sensors.segmentation.boundary_jitter_px, 1);
  EXPECT_TRUE(s.obstacles.empty());
  EXPECT_TRUE(s.terrain.patches.empty());
  EXPECT_EQ(s.slam.mode, "full");
  EXPECT_TRUE(s.slam.config.empty());
}

TEST_F(ConfigLoaderTest, DesignSchemaExampleLoads) {
  Write("slam.yaml", "{}\n");
  const Scenario s = LoadScenario(Write("scen.yaml",
      "name: walking_people\n"
      "seed: 7\n"
      "duration_s: 40\n"
      "physics: {timestep_s: 0.002}\n"
      "world: world.xml\n"
      "robot:\n"
      "  model: rat.xml\n"
      "  start: {xy: [0, 0.5], yaw_deg: 90}\n"
      "  gait: {type: trot, frequency_hz: 3.0, duty: 0.6, step_height_m: 0.015}\n"
      "  command:\n"
      "    waypoints: [[2, 0], [2, 2], [0, 2], [0, 0]]\n"
      "    speed_mps: 0.12\n"
      "    follow: ground_truth\n"
      "  allow_fall: true\n"
      "sensors:\n"
      "  camera: {rate_hz: 20, width: 640, height: 480, fovy_deg: 70, baseline_m: 0.04, noise_std: 2.0}\n"
      "  imu: {rate_hz: 200, accel_noise: 0.02, gyro_noise: 0.002, accel_bias_walk: 0.001, gyro_bias_walk: 0.0001}\n"
      "  joints: {rate_hz: 200, noise_rad: 0.001}\n"
      "  segmentation: {miss_rate: 0.05, dilate_px: 2, latency_frames: 0}\n"
      "obstacles:\n"
      "  - {name: person_1, category: person, path: [[3, -1], [3, 3]], speed_mps: 0.8, start_s: 5, loop: pingpong}\n"
      "  - {name: box_1, category: box, size_m: [0.2, 0.2, 0.2], path: [[1, 1], [1.5, 1]], start_s: 20, speed_mps: 0.2}\n"
      "terrain:\n"
      "  patches: [{center: [1, 0], size: [0.5, 0.5], friction: 0.05}]\n"
      "  slopes: [{center: [3, 0], size: [1, 0.6], angle_deg: 8, yaw_deg: 0}]\n"
      "slam:\n"
      "  mode: full\n"
      "  config: slam.yaml\n"
      "  dynamic: {method: adaptive, alpha: 1.0, beta: 1.0, gamma: 0.5, th_d: 0.1, window_s: 6, window_n: 10}\n"));
  EXPECT_EQ(s.seed, 7u);
  EXPECT_DOUBLE_EQ(s.physics_dt_s, 0.002);
  EXPECT_DOUBLE_EQ(s.robot.start.xy[1], 0.5);
  EXPECT_DOUBLE_EQ(s.robot.start.yaw_deg, 90);
  ASSERT_EQ(s.robot.command.waypoints.size(), 4u);
  EXPECT_DOUBLE_EQ(s.robot.command.waypoints[2][1], 2);
  EXPECT_TRUE(s.robot.allow_fall);
  ASSERT_EQ(s.obstacles.size(), 2u);
  EXPECT_EQ(s.obstacles[0].category, "person");
  EXPECT_EQ(s.obstacles[0].loop, "pingpong");
  EXPECT_DOUBLE_EQ(s.obstacles[1].start_s, 20);
  ASSERT_EQ(s.obstacles[1].size_m.size(), 3u);
  ASSERT_EQ(s.terrain.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(s.terrain.patches[0].friction, 0.05);
  ASSERT_EQ(s.terrain.slopes.size(), 1u);
  EXPECT_DOUBLE_EQ(s.terrain.slopes[0].angle_deg, 8);
  EXPECT_EQ(s.slam.config, (dir_ / "slam.yaml").string());
  EXPECT_EQ(s.slam.dynamic.window_n, 10);
}

// The torque reading's quantisation step under the design's name (torque_quantum_nm) or the
// encoder-style one (torque_resolution_nm): one setting, given once.
TEST_F(ConfigLoaderTest, TorqueQuantumIsTheResolutionsOtherName) {
  const std::string base = std::string(kMinimal) + "sensors:\n  joints: {";
  EXPECT_EQ(LoadScenario(Write("scen.yaml", base + "torque_quantum_nm: 0.004}\n")).sensors.joints.torque_resolution_nm,
            0.004);
  EXPECT_EQ(LoadScenario(Write("scen.yaml", base + "torque_resolution_nm: 0.003}\n")).sensors.joints.torque_resolution_nm,
            0.003);
  const std::string msg = ErrorOf(base + "torque_resolution_nm: 0.003, torque_quantum_nm: 0.004}\n");
  EXPECT_EQ(msg.rfind(ScenPath() + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find("torque_quantum_nm and torque_resolution_nm are one setting"), std::string::npos) << msg;
}

TEST_F(ConfigLoaderTest, UnknownKeyNamesFileLineAndColumn) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "  gati: {duty: 0.5}\n");
  EXPECT_EQ(msg.rfind(ScenPath() + ":5:3: unknown key 'robot.gati' (expected one of: model, ", 0), 0u) << msg;
  EXPECT_NE(msg.find("gait"), std::string::npos) << msg;
}

TEST_F(ConfigLoaderTest, UnknownTopLevelKey) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "sensor:\n  camera: {}\n");
  EXPECT_EQ(msg.rfind(ScenPath() + ":5:1: unknown key 'sensor'", 0), 0u) << msg;
}

TEST_F(ConfigLoaderTest, WrongTypeNamesKeyExpectationAndValue) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "  gait: {duty: abc}\n");
  EXPECT_EQ(msg, ScenPath() + ":5:16: key 'robot.gait.duty' expected a number in (0, 1), got 'abc'");
}

TEST_F(ConfigLoaderTest, WrongTypeListWhereMapExpected) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "sensors: [1, 2]\n");
  EXPECT_EQ(msg, ScenPath() + ":5:10: key 'sensors' expected a map, got a list");
}

TEST_F(ConfigLoaderTest, QuotedNumberIsNotANumber) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "duration_s: \"10\"\n");
  EXPECT_NE(msg.find(":5:13: key 'duration_s' expected a number in (0, 86400]"), std::string::npos) << msg;
}

TEST_F(ConfigLoaderTest, OutOfRangeDuty) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "  gait:\n    duty: 1.5\n");
  EXPECT_EQ(msg, ScenPath() + ":6:11: key 'robot.gait.duty' expected a number in (0, 1), got '1.5'");
}

TEST_F(ConfigLoaderTest, OutOfRangeNegativeRate) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "sensors:\n  imu:\n    rate_hz: -200\n");
  EXPECT_EQ(msg, ScenPath() + ":7:14: key 'sensors.imu.rate_hz' expected a number in (0, 1000], got '-200'");
}

TEST_F(ConfigLoaderTest, OutOfRangeSegmentationKeys) {
  const std::string head = std::string(kMinimal) + "sensors:\n  segmentation:\n";
  EXPECT_EQ(ErrorOf(head + "    false_positive_rate: 1.5\n"),
            ScenPath() + ":7:26: key 'sensors.segmentation.false_positive_rate' expected a number in [0, 1], got '1.5'");
  EXPECT_EQ(ErrorOf(head + "    wrong_category_rate: -0.1\n"),
            ScenPath() + ":7:26: key 'sensors.segmentation.wrong_category_rate' expected a number in [0, 1], got '-0.1'");
  EXPECT_EQ(ErrorOf(head + "    boundary_jitter_px: -1\n"),
            ScenPath() + ":7:25: key 'sensors.segmentation.boundary_jitter_px' expected an integer in [0, 50], got '-1'");
  EXPECT_EQ(ErrorOf(head + "    min_area_px: 150.5\n"),
            ScenPath() + ":7:18: key 'sensors.segmentation.min_area_px' expected an integer in [0, 100000], got '150.5'");
  EXPECT_EQ(ErrorOf(head + "    min_area_px: -1\n"),
            ScenPath() + ":7:18: key 'sensors.segmentation.min_area_px' expected an integer in [0, 100000], got '-1'");
}

TEST_F(ConfigLoaderTest, IntegerKeyRejectsFraction) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "sensors: {camera: {width: 640.5}}\n");
  EXPECT_NE(msg.find(":5:27: key 'sensors.camera.width' expected an integer in [16, 4096], got '640.5'"),
            std::string::npos) << msg;
}

TEST_F(ConfigLoaderTest, BadChoice) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "  gait: {type: gallop}\n");
  EXPECT_EQ(msg, ScenPath() + ":5:16: key 'robot.gait.type' expected one of trot, walk, got 'gallop'");
}

TEST_F(ConfigLoaderTest, SlopeAnglesBeyondTheTerrainsLimitsAreNamedWhereWritten) {
  // The terrain builder takes ramps of up to 30 deg, not flat ones: refused here, with the line.
  const std::string steep =
      ErrorOf(std::string(kMinimal) + "terrain:\n  slopes: [{center: [3, 0], angle_deg: 35}]\n");
  EXPECT_EQ(steep.rfind(ScenPath() + ":6:40: key 'terrain.slopes.0.angle_deg' expected a number in [-30, 30]", 0), 0u)
      << steep;
  const std::string flat = ErrorOf(std::string(kMinimal) + "terrain:\n  slopes: [{center: [3, 0], angle_deg: 0}]\n");
  EXPECT_EQ(flat, ScenPath() + ":6:40: key 'terrain.slopes.0.angle_deg' must not be 0 (a flat ramp; leave the slope out)");
}

TEST_F(ConfigLoaderTest, MissingRequiredKey) {
  const std::string msg = ErrorOf("name: mini\nrobot:\n  model: rat.xml\n");
  EXPECT_EQ(msg, ScenPath() + ":1:1: missing required key 'world'");
  const std::string msg2 = ErrorOf("name: mini\nworld: world.xml\nrobot:\n  allow_fall: true\n");
  EXPECT_EQ(msg2, ScenPath() + ":4:3: missing required key 'robot.model'");
}

TEST_F(ConfigLoaderTest, MissingWorldFile) {
  const std::string msg = ErrorOf("name: mini\nworld: rooms/none.xml\nrobot: {model: rat.xml}\n");
  EXPECT_EQ(msg, ScenPath() + ":2:8: key 'world': file not found: " + (dir_ / "rooms/none.xml").string());
}

TEST_F(ConfigLoaderTest, MissingUrdfBesideRobotModel) {
  Write("other.xml", "<mujoco/>\n");
  const std::string msg = ErrorOf("name: mini\nworld: world.xml\nrobot: {model: other.xml}\n");
  EXPECT_NE(msg.find(":3:16: key 'robot.model': the robot's URDF is missing"), std::string::npos) << msg;
}

TEST_F(ConfigLoaderTest, MissingScenarioFile) {
  const std::string path = (dir_ / "nope.yaml").string();
  try {
    LoadScenario(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": file not found");
  }
}

TEST_F(ConfigLoaderTest, MalformedYamlNamesLineAndColumn) {
  const std::string msg = ErrorOf("name: mini\n  bad: 2\n");
  EXPECT_EQ(msg.rfind(ScenPath() + ":2:6: YAML syntax error: ", 0), 0u) << msg;
  const std::string msg2 = ErrorOf("name: mini\nworld: [world.xml\nrobot: {}\n");
  EXPECT_EQ(msg2.rfind(ScenPath() + ":3:", 0), 0u) << msg2;
}

TEST_F(ConfigLoaderTest, DuplicateKey) {
  const std::string msg = ErrorOf(std::string(kMinimal) + "name: again\n");
  EXPECT_EQ(msg, ScenPath() + ":5:1: duplicate key 'name'");
}

TEST_F(ConfigLoaderTest, ObstacleErrorsNameTheListElement) {
  const std::string msg = ErrorOf(std::string(kMinimal) +
                                  "obstacles:\n"
                                  "  - {name: a, path: [[0, 0]]}\n"
                                  "  - {name: b, path: [[0, 0], [1]]}\n");
  EXPECT_EQ(msg, ScenPath() + ":7:30: key 'obstacles.1.path.1' expected a list of 2 numbers, got a list");
  const std::string dup = ErrorOf(std::string(kMinimal) +
                                  "obstacles:\n"
                                  "  - {name: a, path: [[0, 0]]}\n"
                                  "  - {name: a, path: [[0, 0]]}\n");
  EXPECT_EQ(dup, ScenPath() + ":7:12: obstacle name 'a' is used twice");
  const std::string no_path = ErrorOf(std::string(kMinimal) + "obstacles:\n  - {name: a}\n");
  EXPECT_EQ(no_path, ScenPath() + ":6:5: missing required key 'obstacles.0.path'");
}

TEST_F(ConfigLoaderTest, WaypointsAndVelocityAreExclusive) {
  const std::string msg = ErrorOf(std::string(kMinimal) +
                                  "  command:\n"
                                  "    waypoints: [[1, 0]]\n"
                                  "    velocity: [{t_s: 0, forward_mps: 0.1}]\n");
  EXPECT_NE(msg.find(":7:15: key 'robot.command.velocity': give either waypoints or a velocity schedule"),
            std::string::npos) << msg;
}

TEST_F(ConfigLoaderTest, VelocityScheduleMustMoveForwardInTime) {
  const std::string msg = ErrorOf(std::string(kMinimal) +
                                  "  command:\n"
                                  "    velocity: [{t_s: 2, forward_mps: 0.1}, {t_s: 1, yaw_rate_dps: 10}]\n");
  EXPECT_NE(msg.find("key 'robot.command.velocity.1.t_s' expected a number > 2, got '1'"), std::string::npos)
      << msg;
}

TEST_F(ConfigLoaderTest, SetOverridesNestedAndListValues) {
  const std::string path = Write("scen.yaml", std::string(kMinimal) +
                                 "obstacles:\n"
                                 "  - {name: a, path: [[0, 0], [1, 0]], speed_mps: 0.3}\n"
                                 "  - {name: b, path: [[2, 0]]}\n");
  const Scenario s = LoadScenario(path, {"robot.gait.duty=0.5", "sensors.camera.rate_hz=10",
                                         "obstacles.1.speed_mps=1.5", "robot.command.waypoints=[[1, 2], [3, 4]]",
                                         "terrain.friction=0.8", "seed=42"});
  EXPECT_DOUBLE_EQ(s.robot.gait.duty, 0.5);
  EXPECT_DOUBLE_EQ(s.sensors.camera.rate_hz, 10);
  ASSERT_EQ(s.obstacles.size(), 2u);
  EXPECT_DOUBLE_EQ(s.obstacles[0].speed_mps, 0.3);
  EXPECT_DOUBLE_EQ(s.obstacles[1].speed_mps, 1.5);
  ASSERT_EQ(s.robot.command.waypoints.size(), 2u);
  EXPECT_DOUBLE_EQ(s.robot.command.waypoints[1][0], 3);
  EXPECT_DOUBLE_EQ(s.terrain.friction, 0.8);
  EXPECT_EQ(s.seed, 42u);

  const Scenario empty = LoadScenario(path, {"obstacles=[]"});
  EXPECT_TRUE(empty.obstacles.empty());
}

TEST_F(ConfigLoaderTest, SetWithBadValueNamesTheOverride) {
  const std::string msg = ErrorOf(kMinimal, {"robot.gait.duty=abc"});
  EXPECT_EQ(msg, "--set robot.gait.duty=abc: key 'robot.gait.duty' expected a number in (0, 1), got 'abc'");
}

TEST_F(ConfigLoaderTest, SetUnknownKeyNamesTheOverride) {
  const std::string msg = ErrorOf(kMinimal, {"robot.gait.dutty=0.5"});
  EXPECT_EQ(msg.rfind("--set robot.gait.dutty=0.5: unknown key 'robot.gait.dutty' (expected one of: ", 0), 0u)
      << msg;
  const std::string deep = ErrorOf(kMinimal, {"robot.gati.duty=0.5"});
  EXPECT_EQ(deep.rfind("--set robot.gati.duty=0.5: unknown key 'robot.gati'", 0), 0u) << deep;
}

TEST_F(ConfigLoaderTest, SetMalformedOverrides) {
  EXPECT_EQ(ErrorOf(kMinimal, {"robot.gait.duty"}), "--set robot.gait.duty: expected key.path=value");
  EXPECT_EQ(ErrorOf(kMinimal, {"robot..duty=1"}).rfind("--set robot..duty=1: ", 0), 0u);
  EXPECT_EQ(ErrorOf(kMinimal, {"obstacles.3.speed_mps=1"}).rfind("--set obstacles.3.speed_mps=1: ", 0), 0u);
  EXPECT_EQ(ErrorOf(kMinimal, {"name.x=1"}), "--set name.x=1: 'name' is a single value, it has no key 'x'");
  EXPECT_EQ(ErrorOf(kMinimal, {"robot.gait.duty=[1"}).rfind("--set robot.gait.duty=[1: the value is not valid YAML", 0),
            0u);
}

// Every field of the scenario, compared one by one (source_file excepted).
void ExpectSameScenario(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(a.scoring.slip_travel_m, b.scoring.slip_travel_m);
  EXPECT_EQ(a.scoring.contact_debounce_s, b.scoring.contact_debounce_s);
  EXPECT_EQ(a.scoring.slip_match_before_s, b.scoring.slip_match_before_s);
  EXPECT_EQ(a.scoring.slip_match_after_s, b.scoring.slip_match_after_s);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.duration_s, b.duration_s);
  EXPECT_EQ(a.physics_dt_s, b.physics_dt_s);
  EXPECT_EQ(a.world, b.world);
  const RobotConfig& ra = a.robot;
  const RobotConfig& rb = b.robot;
  EXPECT_EQ(ra.model, rb.model);
  EXPECT_EQ(ra.start.xy, rb.start.xy);
  EXPECT_EQ(ra.start.yaw_deg, rb.start.yaw_deg);
  EXPECT_EQ(ra.gait.type, rb.gait.type);
  EXPECT_EQ(ra.gait.frequency_hz, rb.gait.frequency_hz);
  EXPECT_EQ(ra.gait.duty, rb.gait.duty);
  EXPECT_EQ(ra.gait.step_height_m, rb.gait.step_height_m);
  EXPECT_EQ(ra.command.waypoints, rb.command.waypoints);
  EXPECT_EQ(ra.command.speed_mps, rb.command.speed_mps);
  EXPECT_EQ(ra.command.follow, rb.command.follow);
  EXPECT_EQ(ra.command.loop, rb.command.loop);
  ASSERT_EQ(ra.command.velocity.size(), rb.command.velocity.size());
  for (size_t i = 0; i < ra.command.velocity.size(); ++i) {
    EXPECT_EQ(ra.command.velocity[i].t_s, rb.command.velocity[i].t_s);
    EXPECT_EQ(ra.command.velocity[i].forward_mps, rb.command.velocity[i].forward_mps);
    EXPECT_EQ(ra.command.velocity[i].yaw_rate_dps, rb.command.velocity[i].yaw_rate_dps);
  }
  EXPECT_EQ(ra.allow_fall, rb.allow_fall);
  const SensorsConfig& sa = a.sensors;
  const SensorsConfig& sb = b.sensors;
  EXPECT_EQ(sa.camera.rate_hz, sb.camera.rate_hz);
  EXPECT_EQ(sa.camera.width, sb.camera.width);
  EXPECT_EQ(sa.camera.height, sb.camera.height);
  EXPECT_EQ(sa.camera.fovy_deg, sb.camera.fovy_deg);
  EXPECT_EQ(sa.camera.baseline_m, sb.camera.baseline_m);
  EXPECT_EQ(sa.camera.noise_std, sb.camera.noise_std);
  EXPECT_EQ(sa.camera.depth, sb.camera.depth);
  EXPECT_EQ(sa.camera.segmentation, sb.camera.segmentation);
  EXPECT_EQ(sa.imu.rate_hz, sb.imu.rate_hz);
  EXPECT_EQ(sa.imu.accel_noise, sb.imu.accel_noise);
  EXPECT_EQ(sa.imu.gyro_noise, sb.imu.gyro_noise);
  EXPECT_EQ(sa.imu.accel_bias_walk, sb.imu.accel_bias_walk);
  EXPECT_EQ(sa.imu.gyro_bias_walk, sb.imu.gyro_bias_walk);
  EXPECT_EQ(sa.joints.rate_hz, sb.joints.rate_hz);
  EXPECT_EQ(sa.joints.noise_rad, sb.joints.noise_rad);
  EXPECT_EQ(sa.joints.resolution_rad, sb.joints.resolution_rad);
  EXPECT_EQ(sa.segmentation.miss_rate, sb.segmentation.miss_rate);
  EXPECT_EQ(sa.segmentation.dilate_px, sb.segmentation.dilate_px);
  EXPECT_EQ(sa.segmentation.latency_frames, sb.segmentation.latency_frames);
  EXPECT_EQ(sa.segmentation.min_area_px, sb.segmentation.min_area_px);
  EXPECT_EQ(sa.segmentation.false_positive_rate, sb.segmentation.false_positive_rate);
  EXPECT_EQ(sa.segmentation.wrong_category_rate, sb.segmentation.wrong_category_rate);
  EXPECT_EQ(sa.segmentation.boundary_jitter_px, sb.segmentation.boundary_jitter_px);
  ASSERT_EQ(a.obstacles.size(), b.obstacles.size());
  for (size_t i = 0; i < a.obstacles.size(); ++i) {
    const ObstacleConfig& oa = a.obstacles[i];
    const ObstacleConfig& ob = b.obstacles[i];
    EXPECT_EQ(oa.name, ob.name);
    EXPECT_EQ(oa.category, ob.category);
    EXPECT_EQ(oa.size_m, ob.size_m);
    EXPECT_EQ(oa.path, ob.path);
    EXPECT_EQ(oa.speed_mps, ob.speed_mps);
    EXPECT_EQ(oa.start_s, ob.start_s);
    EXPECT_EQ(oa.pause_s, ob.pause_s);
    EXPECT_EQ(oa.loop, ob.loop);
    EXPECT_EQ(oa.yaw_deg, ob.yaw_deg);
  }
  EXPECT_EQ(a.terrain.friction, b.terrain.friction);
  ASSERT_EQ(a.terrain.patches.size(), b.terrain.patches.size());
  for (size_t i = 0; i < a.terrain.patches.size(); ++i) {
    EXPECT_EQ(a.terrain.patches[i].center, b.terrain.patches[i].center);
    EXPECT_EQ(a.terrain.patches[i].size, b.terrain.patches[i].size);
    EXPECT_EQ(a.terrain.patches[i].friction, b.terrain.patches[i].friction);
  }
  ASSERT_EQ(a.terrain.slopes.size(), b.terrain.slopes.size());
  for (size_t i = 0; i < a.terrain.slopes.size(); ++i) {
    EXPECT_EQ(a.terrain.slopes[i].center, b.terrain.slopes[i].center);
    EXPECT_EQ(a.terrain.slopes[i].size, b.terrain.slopes[i].size);
    EXPECT_EQ(a.terrain.slopes[i].angle_deg, b.terrain.slopes[i].angle_deg);
    EXPECT_EQ(a.terrain.slopes[i].yaw_deg, b.terrain.slopes[i].yaw_deg);
  }
  EXPECT_EQ(a.slam.mode, b.slam.mode);
  EXPECT_EQ(a.slam.config, b.slam.config);
  EXPECT_EQ(a.slam.dynamic.method, b.slam.dynamic.method);
  EXPECT_EQ(a.slam.dynamic.alpha, b.slam.dynamic.alpha);
  EXPECT_EQ(a.slam.dynamic.beta, b.slam.dynamic.beta);
  EXPECT_EQ(a.slam.dynamic.gamma, b.slam.dynamic.gamma);
  EXPECT_EQ(a.slam.dynamic.th_d, b.slam.dynamic.th_d);
  EXPECT_EQ(a.slam.dynamic.window_s, b.slam.dynamic.window_s);
  EXPECT_EQ(a.slam.dynamic.window_n, b.slam.dynamic.window_n);
}

TEST_F(ConfigLoaderTest, ScenarioToYamlRoundTrip) {
  Write("cfg/slam.yaml", "{}\n");
  const std::string path = Write("scen.yaml",
      "name: round-trip.1\n"
      "seed: 18446744073709551615\n"
      "duration_s: 12.345678901234567\n"
      "physics: {timestep_s: 0.0015}\n"
      "world: ./world.xml\n"
      "robot:\n"
      "  model: rat.xml\n"
      "  start: {xy: [-0.1, 0.3], yaw_deg: -45}\n"
      "  gait: {type: walk, frequency_hz: 2.2, duty: 0.75, step_height_m: 0.02}\n"
      "  command:\n"
      "    velocity: [{t_s: 0, forward_mps: 0.1}, {t_s: 3.3, forward_mps: 0.05, yaw_rate_dps: -20}]\n"
      "    follow: estimate\n"
      "    loop: true\n"
      "    speed_mps: 0.2\n"
      "  allow_fall: true\n"
      "sensors:\n"
      "  camera: {rate_hz: 15, width: 320, height: 240, fovy_deg: 60.5, baseline_m: 0.05, noise_std: 0,"
      " depth: false, segmentation: false}\n"
      "  imu: {rate_hz: 400, accel_noise: 0.03, gyro_noise: 0.003, accel_bias_walk: 0.002, gyro_bias_walk: 1e-5}\n"
      "  joints: {rate_hz: 100, noise_rad: 0.002, resolution_rad: 0}\n"
      "  segmentation: {miss_rate: 0.1, dilate_px: 3, latency_frames: 1, min_area_px: 80,"
      " false_positive_rate: 0.015, wrong_category_rate: 0.1234567, boundary_jitter_px: 2}\n"
      "obstacles:\n"
      "  - {name: p1, category: person, size_m: [1.7], path: [[3, -1], [3, 3]], speed_mps: 0.8, start_s: 5,"
      " pause_s: 1.5, loop: pingpong, yaw_deg: 30}\n"
      "  - {name: ball, category: ball, path: [[1, 1]]}\n"
      "terrain:\n"
      "  friction: 0.9\n"
      "  patches: [{center: [1, 0], size: [0.5, 0.7], friction: 0.05}]\n"
      "  slopes: [{center: [3, 0.1], size: [1.2, 0.6], angle_deg: -6, yaw_deg: 180}]\n"
      "slam:\n"
      "  mode: visual_dynamic\n"
      "  config: cfg/slam.yaml\n"
      "  dynamic: {method: paper, alpha: 1.1, beta: 0.9, gamma: 0.4, th_d: 0.12, window_s: 5.5, window_n: 12}\n"
      "scoring: {slip_travel_m: 0.0045, contact_debounce_s: 0.002, slip_match_before_s: 0.01, slip_match_after_s: 0.05}\n");
  const Scenario first = LoadScenario(path, {"obstacles.1.speed_mps=0.1"});
  EXPECT_EQ(first.scoring.slip_travel_m, 0.0045);
  EXPECT_EQ(first.scoring.slip_match_after_s, 0.05);
  const std::string yaml = ScenarioToYaml(first);
  // Written elsewhere: the paths inside are absolute, so the file loads from any folder.
  const std::string copy = Write("elsewhere/resolved.yaml", yaml);
  const Scenario second = LoadScenario(copy);
  ExpectSameScenario(first, second);
  EXPECT_EQ(ScenarioToYaml(second), yaml);
  EXPECT_EQ(second.obstacles[1].speed_mps, 0.1);
  EXPECT_EQ(second.sensors.segmentation.min_area_px, 80);
  EXPECT_EQ(second.sensors.segmentation.false_positive_rate, 0.015);
  EXPECT_EQ(second.sensors.segmentation.wrong_category_rate, 0.1234567);
  EXPECT_EQ(second.sensors.segmentation.boundary_jitter_px, 2);

  // Defaults round-trip too.
  const Scenario minimal = LoadScenario(Write("scen.yaml", kMinimal));
  ExpectSameScenario(minimal, LoadScenario(Write("elsewhere/minimal.yaml", ScenarioToYaml(minimal))));
}

// Every scenario shipped in scenarios/ loads, and its resolved form loads back to the same.
TEST(ShippedScenarios, AllLoadAndRoundTrip) {
  const fs::path dir = fs::path(VIQU_SOURCE_DIR) / "scenarios";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no scenarios/ folder";
  std::string tmpl = (fs::temp_directory_path() / "viqu_shipped_XXXXXX").string();
  ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    Scenario s;
    try {
      s = LoadScenario(entry.path().string());
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    const fs::path copy = fs::path(tmpl) / entry.path().filename();
    std::ofstream(copy) << ScenarioToYaml(s);
    EXPECT_EQ(ScenarioToYaml(LoadScenario(copy.string())), ScenarioToYaml(s));
    ++count;
  }
  fs::remove_all(tmpl);
  std::printf("loaded %zu shipped scenarios\n", count);
}

// The YAML reader takes a file of up to 16 MiB whole (read in chunks) and refuses a larger one.
TEST(YamlFileText, ReadsWholeFilesUpToTheLimitAndRefusesLarger) {
  const fs::path dir = fs::temp_directory_path() / "viqu_yaml_text";
  fs::create_directories(dir);
  // Crosses the 64 KiB read chunks: 2 chunks and 17 bytes, every byte checked.
  std::string medium;
  for (size_t i = 0; i < 2 * 65536 + 17; ++i) medium.push_back(static_cast<char>('a' + i % 26));
  std::ofstream(dir / "medium.yaml", std::ios::binary) << medium;
  EXPECT_EQ(ReadYamlFileText((dir / "medium.yaml").string()), medium);
  std::ofstream(dir / "empty.yaml", std::ios::binary) << "";
  EXPECT_EQ(ReadYamlFileText((dir / "empty.yaml").string()), "");
  const size_t limit = size_t{16} << 20;
  std::ofstream(dir / "at_limit.yaml", std::ios::binary) << std::string(limit, '#');
  EXPECT_EQ(ReadYamlFileText((dir / "at_limit.yaml").string()).size(), limit);
  std::ofstream(dir / "over.yaml", std::ios::binary) << std::string(limit + 1, '#');
  try {
    ReadYamlFileText((dir / "over.yaml").string());
    ADD_FAILURE() << "a file over 16 MiB was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("over.yaml: larger than 16 MiB"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace viqu

namespace viqu {
namespace {

// A second YAML document is found by its marker line, without parsing it: "---" after content,
// or content after "...". Markers before any content (an OpenCV file's "%YAML:1.0" then "---"),
// in comments or indented inside a block scalar are no second document.
TEST(YamlDocuments, ASecondDocumentIsNamedByItsMarkerLine) {
  const auto error_of = [](const std::string& text) -> std::string {
    try {
      LoadYamlText(text, "f.yaml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of("a: 1\n---\nb: 2\n").rfind("f.yaml:2:1: a second YAML document", 0), 0u);
  EXPECT_EQ(error_of("a: 1\n...\n# end\nb: 2\n").rfind("f.yaml:4:1: a second YAML document", 0), 0u);
  EXPECT_EQ(error_of("# head\n---\na: 1\n"), "");
  EXPECT_EQ(error_of("%YAML 1.2\n---\na: 1\n...\n"), "");
  EXPECT_EQ(error_of("--- # the only one\na: |\n  ---\n  text\n"), "");
  EXPECT_EQ(error_of("a: '---'\nb: -- -\n"), "");
}

// An input on which yaml-cpp's LoadAll never returns (found by fuzz_scenario_loader): the loader
// reads one document, refuses it, and returns. (A hang here ends at CTest's timeout.)
TEST(YamlDocuments, AnInputThatHangsLoadAllIsRefusedAtOnce) {
  EXPECT_THROW(LoadScenario(std::string(VIQU_SOURCE_DIR) + "/tests/data/yaml_loadall_hang.yaml"), InputError);
}

}  // namespace
}  // namespace viqu

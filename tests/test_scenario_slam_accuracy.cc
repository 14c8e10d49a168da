// Accuracy targets of the SLAM core (issue 3) against ground truth: the full static_room and
// long_loop scenarios with live stereo SLAM (sync mapping, deterministic). ATE RMSE is at most
// 0.3% (static_room) and 0.6% (long_loop) of the path, and no frame is lost in these static scenes.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"
#include "slam/eval/trajectory.h"
#include "slam/eval/trajectory_error.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

// The run folder of the scenario run `tag`.
fs::path RunDir(const std::string& tag) { return fs::temp_directory_path() / ("viqu_slam_accuracy_" + tag); }

YAML::Node RunAndReadMetrics(const std::string& scenario_file, const std::string& tag) {
  const Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/" + scenario_file, {});
  const fs::path dir = RunDir(tag);
  fs::remove_all(dir);
  runner::RunOptions opt;
  opt.out_dir = dir.string();
  EXPECT_EQ(runner::RunScenario(s, opt), 0);
  EXPECT_TRUE(fs::exists(dir / "trajectory_est.txt"));
  // metrics.json is JSON, which YAML reads.
  return YAML::LoadFile((dir / "metrics.json").string());
}

void ExpectAccuracy(const YAML::Node& m, double max_pct_path) {
  const double pct = m["ate"]["rmse_pct_path"].as<double>();
  const int frames = m["tracking"]["frames"].as<int>();
  const int lost = m["tracking"]["lost_frames"].as<int>();
  std::printf("ATE %.4f m RMSE = %.3f%% of %.2f m path; %d lost of %d frames; %d keyframes\n",
              m["ate"]["rmse_m"].as<double>(), pct, m["path_length_m"].as<double>(), lost, frames,
              m["tracking"]["keyframes"].as<int>());
  EXPECT_LE(pct, max_pct_path);
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(frames, m["camera"]["frames"].as<int>());            // a pose for every frame
  EXPECT_EQ(m["ate"]["pairs"].as<int>(), frames);                // and every pose evaluated
}

// The Sim(3) keys: recomputed from the run's own trajectory files, and the scale error every
// stereo run shares (docs/MEASURED.md "Scale, session 29": the estimate is 0.2-0.4% short of the truth;
// scale 1.0018 on static_room and 1.0029 on long_loop when this was written; bound about 2x the
// larger).
void ExpectSim3(const YAML::Node& m, const std::string& tag) {
  const fs::path dir = RunDir(tag);
  const eval::AteResult sim3 = eval::ComputeAte(eval::ReadTumTrajectory((dir / "trajectory_est.txt").string()),
                                                eval::ReadTumTrajectory((dir / "trajectory_gt.txt").string()), true);
  const double rmse = m["ate"]["rmse_m"].as<double>(), rmse_sim3 = m["ate"]["sim3_rmse_m"].as<double>();
  const double scale = m["ate"]["sim3_scale"].as<double>();
  std::printf("Sim(3): ATE %.4f m (SE(3) %.4f m), scale %.5f: the estimate %.2f%% short\n", rmse_sim3, rmse, scale,
              100 * (1 - 1 / scale));
  EXPECT_NEAR(rmse_sim3, sim3.ate.rmse, 1e-7);  // metrics.json keeps 9 digits
  EXPECT_NEAR(scale, sim3.alignment.scale, 1e-7);
  EXPECT_LE(rmse_sim3, rmse + 1e-12);  // a scale can only lower the least-squares error
  EXPECT_LT(std::abs(scale - 1), 0.006);
}

TEST(SlamAccuracy, StaticRoomWithinPointThreePercentOfPath) {
  const YAML::Node m = RunAndReadMetrics("static_room.yaml", "static_room");
  ExpectAccuracy(m, 0.3);
  ExpectSim3(m, "static_room");
  // Leg odometry + IMU alone over the same run (issue 8): drift target 5% of the path; measured
  // 1.70% and ATE 35 mm when written, 2.63% and 53 mm since the touch-down inflation went
  // horizontal-only (session 11) and the speed gate (session 17); bounds at about 2x of the first.
  const double drift = m["lo"]["drift_pct_path"].as<double>();
  std::printf("LO alone: ATE %.4f m, drift %.2f%% of path, yaw drift %.1f deg, %.4f ms per sample\n",
              m["lo"]["ate"]["rmse_m"].as<double>(), drift, m["lo"]["yaw_drift_deg"].as<double>(),
              m["lo"]["update_ms_mean"].as<double>());
  EXPECT_LE(drift, 3.4);
  EXPECT_LE(m["lo"]["ate"]["rmse_m"].as<double>(), 0.07);
  // The gyro bias about the vertical, found from pairs of stance feet (session 18): measured
  // 0.98 mrad/s against the simulated gyro's 1.11 at the end (the filter without it keeps the
  // start's 0: an error of 1.11), 92 pieces used, 141 left out while turning; yaw drift 3.7 deg
  // (5.5 without). The bound is about 3x the error measured.
  const double bias = m["lo"]["gyro_bias_z_radps"].as<double>();
  const double true_bias = m["lo"]["true_gyro_bias_z_radps"].as<double>();
  std::printf("gyro bias about z: %.2f mrad/s found, %.2f true; %d stance-pair pieces used, %d turning\n", bias * 1e3,
              true_bias * 1e3, m["lo"]["yaw_bias_pieces"].as<int>(), m["lo"]["yaw_bias_turning"].as<int>());
  EXPECT_LT(std::abs(bias - true_bias), 0.0004);
  EXPECT_GE(m["lo"]["yaw_bias_pieces"].as<int>(), 50);
}

TEST(SlamAccuracy, LongLoopWithinPointSixPercentOfPath) {
  const YAML::Node m = RunAndReadMetrics("long_loop.yaml", "long_loop");
  ExpectAccuracy(m, 0.6);
  ExpectSim3(m, "long_loop");
}

}  // namespace
}  // namespace viqu

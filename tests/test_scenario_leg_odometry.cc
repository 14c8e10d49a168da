// Leg odometry + IMU and its fusion with vision (issue 8) on whole scenarios, against ground
// truth. Bounds are the measured figures with about 2x margin (docs/MEASURED.md, "Leg odometry + IMU and fusion").
//  - camera_dropout: a 5 s black-camera outage while walking; `full` carries the pose on the
//    filter and resumes, `visual` dead-reckons on its last velocity.
//  - static_room steered by the fused estimate (robot.command.follow: estimate) closes its 2 m
//    square as it does steered by ground truth.
//  - slippery_patch: the robot walks onto ice and treads in place; the slip decision must report
//    the stances whose feet slide, and hardly any that do not.
//  - blank_wall: a plain board fills the view; `full` carries the pose where vision loses it.
//  - ice_patches: three strips of ice across the path; short skids at touch-down, the slip
//    decision's hard case (its targets are missed there: the bounds hold today's figures).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

struct RunOutput {
  YAML::Node metrics;
  fs::path dir;
};

RunOutput RunScenario(const std::string& file, const std::string& tag, const std::vector<std::string>& sets) {
  const Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/" + file, sets);
  RunOutput r;
  r.dir = fs::temp_directory_path() / ("viqu_lo_" + tag);
  fs::remove_all(r.dir);
  runner::RunOptions opt;
  opt.out_dir = r.dir.string();
  EXPECT_EQ(runner::RunScenario(s, opt), 0);
  r.metrics = YAML::LoadFile((r.dir / "metrics.json").string());
  return r;
}

int Lines(const fs::path& p) {
  std::ifstream in(p);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != '#';
  return n;
}

TEST(LegOdometryScenario, CameraDropoutIsCarriedByTheFilter) {
  const RunOutput full = RunScenario("camera_dropout.yaml", "dropout_full", {});
  const RunOutput visual = RunScenario("camera_dropout.yaml", "dropout_visual", {"slam.mode=visual"});
  const RunOutput seen = RunScenario("camera_dropout.yaml", "dropout_none", {"sensors.camera.dropouts=[]"});
  const double ate_full = full.metrics["ate"]["rmse_m"].as<double>();
  const double ate_visual = visual.metrics["ate"]["rmse_m"].as<double>();
  const double ate_seen = seen.metrics["ate"]["rmse_m"].as<double>();
  const int frames = full.metrics["tracking"]["frames"].as<int>();
  std::printf("camera_dropout: ATE full %.4f m, visual %.4f m (%.3fx), full without the dropout %.4f m (%.2fx); lost "
              "%d / %d frames; LO alone %.4f m, drift %.2f%%\n",
              ate_full, ate_visual, ate_full / ate_visual, ate_seen, ate_full / ate_seen,
              full.metrics["tracking"]["lost_frames"].as<int>(), frames, full.metrics["lo"]["ate"]["rmse_m"].as<double>(),
              full.metrics["lo"]["drift_pct_path"].as<double>());
  // A pose for every frame, the 100 black frames included (no gap).
  EXPECT_EQ(Lines(full.dir / "trajectory_est.txt"), frames);
  EXPECT_EQ(Lines(full.dir / "trajectory_lo.txt"), frames);
  EXPECT_EQ(full.metrics["tracking"]["lost_frames"].as<int>(), 100);  // 14 s to 19 s at 20 Hz, no more
  // Measured 3.3 mm (full), 131 mm (visual; 144.6 mm in session 25, carry on or off: black frames
  // carry nothing) and 2.2 mm without the dropout (1.49x; the issue asks
  // <= 2x; 6.2x while the touch-down inflation also down-weighted the vertical and the height
  // sank 25 mm in the outage's corner turn). Session 39, with the held gravity and the gyro bias
  // from vision on by default: 3.7 mm, visual 141.7 mm, 2.0 mm without the dropout (1.82x).
  EXPECT_LT(ate_full, 0.007);
  EXPECT_LT(ate_full, 0.2 * ate_visual);
  EXPECT_LT(ate_full, 3.0 * ate_seen);
  EXPECT_EQ(seen.metrics["tracking"]["lost_frames"].as<int>(), 0);
  EXPECT_FALSE(fs::exists(visual.dir / "trajectory_lo.txt"));  // no filter in mode visual
}

// The camera dark from the very start (no map yet): the filter carries the pose, and the first
// map starts where the robot has walked to, not at its starting pose.
TEST(LegOdometryScenario, ADropoutAtTheStartIsCarriedByTheFilterToo) {
  const RunOutput r = RunScenario("camera_dropout.yaml", "dropout_at_start",
                                  {"duration_s=3", "sensors.camera.dropouts=[[0, 1.0]]"});
  const double ate = r.metrics["ate"]["rmse_m"].as<double>();
  std::printf("camera_dropout, 3 s dark from the start for 1 s: ATE %.4f m (%.2f%% of path), %d lost of %d frames\n", ate,
              r.metrics["ate"]["rmse_pct_path"].as<double>(), r.metrics["tracking"]["lost_frames"].as<int>(),
              r.metrics["tracking"]["frames"].as<int>());
  EXPECT_EQ(r.metrics["tracking"]["lost_frames"].as<int>(), 20);  // 0 to 1 s at 20 Hz
  EXPECT_EQ(Lines(r.dir / "trajectory_est.txt"), r.metrics["tracking"]["frames"].as<int>());
  // Measured 0.8 mm; 36.4 mm before session 45, when the estimate stood at the start pose
  // through the outage and the map began there (the robot had walked 0.1 m). Bound: 2x.
  EXPECT_LT(ate, 0.0016);
}

TEST(LegOdometryScenario, SlipperyPatchFlagsSlidingFeet) {
  const RunOutput r = RunScenario("slippery_patch.yaml", "slippery", {});
  const YAML::Node& slip = r.metrics["slip"];
  std::printf("slippery_patch: slip precision %.3f recall %.3f (%d true events, %d detected); LO ATE %.3f m, drift "
              "%.1f%%; SLAM ATE %.4f m\n",
              slip["precision"].as<double>(), slip["recall"].as<double>(), slip["truth_events"].as<int>(),
              slip["events"].as<int>(), r.metrics["lo"]["ate"]["rmse_m"].as<double>(),
              r.metrics["lo"]["drift_pct_path"].as<double>(), r.metrics["ate"]["rmse_m"].as<double>());
  // Scored by issue 55's definitions (docs/LEG_ODOMETRY.md), measured 2026-12-07: 859 true
  // events (stances whose sole travelled over 3 mm); the slip decision 0.91 / 0.83 (781
  // detected), the velocity gates' flags 0.82 / 0.86, the oracle 1.00 / 0.93. Bounds at about
  // twice the misses.
  EXPECT_GE(slip["truth_events"].as<int>(), 500);
  EXPECT_GE(slip["precision"].as<double>(), 0.82);
  EXPECT_GE(slip["recall"].as<double>(), 0.66);
  // slip.csv lists every event of both kinds.
  EXPECT_EQ(Lines(r.dir / "slip.csv") - 1, slip["truth_events"].as<int>() + slip["events"].as<int>());
  // The filter fused with vision makes the same decision on its own feet (slip.fused.*): measured
  // 0.91 / 0.83; vision bounds its error but does not make it see feet that slide together
  // (test_leg_odometry).
  const YAML::Node& fused = slip["fused"];
  std::printf("slippery_patch, the filter fused with vision: slip precision %.3f recall %.3f (%d detected)\n",
              fused["precision"].as<double>(), fused["recall"].as<double>(), fused["events"].as<int>());
  EXPECT_GE(fused["precision"].as<double>(), 0.82);
  EXPECT_GE(fused["recall"].as<double>(), 0.66);
  // Vision is unaffected by the ice: measured 0.43 mm (9.5 mm when this test was written).
  EXPECT_LT(r.metrics["ate"]["rmse_m"].as<double>(), 0.02);
}

TEST(LegOdometryScenario, BlankWallIsCarriedByTheFilter) {
  const RunOutput full = RunScenario("blank_wall.yaml", "blank_full", {});
  const RunOutput visual = RunScenario("blank_wall.yaml", "blank_visual", {"slam.mode=visual"});
  const double ate_full = full.metrics["ate"]["rmse_m"].as<double>();
  const double ate_visual = visual.metrics["ate"]["rmse_m"].as<double>();
  const int frames = full.metrics["tracking"]["frames"].as<int>();
  const int lost_full = full.metrics["tracking"]["lost_frames"].as<int>();
  std::printf("blank_wall: ATE full %.4f m, visual %.4f m (%.3fx); lost %d (full) and %d (visual) of %d frames; LO "
              "alone %.4f m\n",
              ate_full, ate_visual, ate_full / ate_visual, lost_full, visual.metrics["tracking"]["lost_frames"].as<int>(),
              frames, full.metrics["lo"]["ate"]["rmse_m"].as<double>());
  // The close-up starves vision: it loses track in both modes (measured 44 and 64 frames; 44 and
  // 46 since session 25; 65 and 49 since session 27, where a frame needs 30 map points among its
  // inliers).
  EXPECT_GE(lost_full, 10);
  // A pose for every frame in full, the lost ones carried by the filter.
  EXPECT_EQ(Lines(full.dir / "trajectory_est.txt"), frames);
  // Measured 25.1 mm (full) and 753.5 mm (visual, which dead-reckoned on its last velocity);
  // 26.6 mm and 339.9 mm (0.078x) since session 25, where visual carries its lost frames by the
  // last frame's points while the wall still shows some (46 lost frames); 15.4 mm and 339.5 mm
  // (0.045x) since session 27.
  // Until session 36 full was not better than the filter alone here (24.3 mm): vision's last poses
  // on the floor strip tilt by 3-5 deg, the filter took their orientation, and the map resumed
  // tilted (16.1 mm, the height 70 mm off at the end). The tilt gate (lo.fusion_tilt_gate_deg)
  // levels them to the IMU's mean force, and the carry gate keeps the carried orientation within
  // 1 deg of it, so the new segment starts level: measured 7.8 mm with 6 levellings; 5.8 mm
  // against visual's 376.6 mm (44 and 48 lost frames) in session 39.
  EXPECT_GE(full.metrics["lo"]["levellings"].as<int>(), 1);
  EXPECT_LT(ate_full, 0.015);
  EXPECT_LT(ate_full, 0.16 * ate_visual);
}

// The trunk's true xy at the first and the last encoder sample, from lo.csv (columns true_x, true_y).
std::pair<Eigen::Vector2d, Eigen::Vector2d> TrueStartAndEnd(const fs::path& lo_csv) {
  std::ifstream in(lo_csv);
  std::string line;
  std::getline(in, line);  // header: t_s,x,y,z,vx,vy,vz,true_x,true_y,...
  std::vector<Eigen::Vector2d> xy;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    for (int i = 0; i < 9 && std::getline(ss, cell, ','); ++i) v.push_back(std::stod(cell));
    if (v.size() == 9) xy.emplace_back(v[7], v[8]);
  }
  EXPECT_GE(xy.size(), 2u);
  if (xy.size() < 2) return {};
  return {xy.front(), xy.back()};
}

TEST(LegOdometryScenario, ClosedLoopOnTheEstimateClosesTheSquare) {
  const RunOutput r = RunScenario("static_room.yaml", "closed_loop", {"robot.command.follow=estimate"});
  EXPECT_EQ(r.metrics["robot"]["steer_source"].as<std::string>(), "estimate");
  const auto [start, end] = TrueStartAndEnd(r.dir / "lo.csv");
  const double gap = (end - start).norm();
  std::printf("static_room steered by the estimate: ends %.3f m (truth) from its start; ATE %.4f m\n", gap,
              r.metrics["ate"]["rmse_m"].as<double>());
  EXPECT_LE(gap, 0.15);  // the target; by ground truth the square ends within it too
  EXPECT_GE(r.metrics["path_length_m"].as<double>(), 7.5);  // the whole square was walked
}

// ice_patches is the slip suite's case where the targets are missed (docs/MEASURED.md, "Leg odometry +
// IMU"): the skids on its short ice strips are 20-40 ms at 0.05-0.15 m/s and look like the
// landing itself through the encoders, and its leg-odometry drift is not the ice's (3.28% on the
// same walk without ice). The bounds hold today's figures with about 2x margin on what each
// measures, so that a regression in the gate, the filter or the fusion shows here.
TEST(LegOdometryScenario, IcePatchesSkidsAreFlaggedAndFusionStaysBelowVision) {
  const RunOutput full = RunScenario("ice_patches.yaml", "ice_full", {});
  const RunOutput visual = RunScenario("ice_patches.yaml", "ice_visual", {"slam.mode=visual"});
  const RunOutput ungated =
      RunScenario("ice_patches.yaml", "ice_ungated", {"slam.lo.slip_gate_chi2=1e9", "slam.lo.slip_speed_mps=1e9"});
  const double ate_full = full.metrics["ate"]["rmse_m"].as<double>();
  const double ate_visual = visual.metrics["ate"]["rmse_m"].as<double>();
  const YAML::Node& slip = full.metrics["slip"];
  const double drift = full.metrics["lo"]["drift_pct_path"].as<double>();
  const double drift_ungated = ungated.metrics["lo"]["drift_pct_path"].as<double>();
  const YAML::Node& gate = slip["gate"];
  std::printf("ice_patches: ATE full %.4f m, visual %.4f m (%.3fx); slip by travel precision %.3f recall %.3f (%d true "
              "events, %d detected, %.2f false per m); the gates' flags %.3f / %.3f (%d, %.1f per m); oracle %.3f / "
              "%.3f; contact %.3f; normal force RMSE %.2f N; LO drift %.2f%%, gates off %.2f%% (%.3fx)\n",
              ate_full, ate_visual, ate_full / ate_visual, slip["precision"].as<double>(), slip["recall"].as<double>(),
              slip["truth_events"].as<int>(), slip["events"].as<int>(), slip["false_per_m"].as<double>(),
              gate["precision"].as<double>(), gate["recall"].as<double>(), gate["events"].as<int>(),
              gate["false_per_m"].as<double>(), slip["oracle"]["precision"].as<double>(),
              slip["oracle"]["recall"].as<double>(), full.metrics["contact"]["accuracy"].as<double>(),
              full.metrics["grf"]["normal_rmse_n"].as<double>(), drift, drift_ungated, drift / drift_ungated);
  // Scored by issue 55's definitions (a stance whose sole travels over 3 mm; one-to-one matching;
  // docs/leg_odometry.md), measured 2026-12-07: 21 true events; the slip by travel 0.80 / 0.57
  // (15 detected, 1.0 false per m), the velocity gates' flags 0.09 / 0.86 (199 detected, 62.9 per
  // m), the oracle 0.64 / 0.76; contact 0.966 of samples; normal force RMSE 1.30 N. Bounds at
  // about twice the misses (precision, contact) or twice the figure (false per m, force), and the
  // reported decision well above the gates' precision, so that scoring the gates again fails here.
  EXPECT_GE(slip["truth_events"].as<int>(), 10);
  EXPECT_GE(slip["precision"].as<double>(), 0.6);
  EXPECT_GE(slip["recall"].as<double>(), 0.3);
  EXPECT_LE(slip["false_per_m"].as<double>(), 2.0);
  EXPECT_GT(slip["precision"].as<double>(), 3 * gate["precision"].as<double>());
  EXPECT_GE(full.metrics["contact"]["accuracy"].as<double>(), 0.93);
  EXPECT_LE(full.metrics["grf"]["normal_rmse_n"].as<double>(), 1.6);
  // With both gates off they flag nothing, and the filter drifts no less: measured 1.78% gated
  // against 1.90% (0.94x; the target is 0.6x). The slip by travel reports, it does not
  // gate: the same with the gates off.
  EXPECT_EQ(ungated.metrics["slip"]["gate"]["events"].as<int>(), 0);
  EXPECT_LT(drift, 3.6);
  EXPECT_LE(drift, 1.05 * drift_ungated);
  // Measured 2.2 mm (full) against 2.7 mm (visual), 0.81x, until session 33; 3.1 against 2.4 mm
  // (1.33x) since its fusion check (docs/MEASURED.md "Point fusion, session 33"); 2.9 against 2.3 mm (1.25x)
  // in session 39. No lost frame in either.
  EXPECT_LT(ate_full, 0.0045);
  EXPECT_EQ(full.metrics["tracking"]["lost_frames"].as<int>(), 0);
  // Issue 8's "full <= visual + 5%" over seeds 2-6, as docs/MEASURED.md measures it: one seed's ratio
  // moves between 0.40x and 1.25x (session 33), so a single seed's cannot hold the target.
  // Measured 2.58 against 3.39 mm (0.76x; 0.65x before session 33; target 0.7x); 2.11 against
  // 3.39 mm (0.62x) since session 38's defaults (held gravity, gyro bias from vision), and over
  // seeds 2-12 (`viqu sweep`, session 39) 2.30 against 3.40 mm (0.68x).
  double sum_full = 0, sum_visual = 0;
  for (int seed = 2; seed <= 6; ++seed) {
    const std::string n = std::to_string(seed);
    const RunOutput f = RunScenario("ice_patches.yaml", "ice_full_seed" + n, {"seed=" + n});
    const RunOutput v = RunScenario("ice_patches.yaml", "ice_visual_seed" + n, {"seed=" + n, "slam.mode=visual"});
    sum_full += f.metrics["ate"]["rmse_m"].as<double>();
    sum_visual += v.metrics["ate"]["rmse_m"].as<double>();
    std::printf("ice_patches seed %d: ATE full %.4f m, visual %.4f m\n", seed, f.metrics["ate"]["rmse_m"].as<double>(),
                v.metrics["ate"]["rmse_m"].as<double>());
  }
  std::printf("ice_patches seeds 2-6: mean ATE full %.4f m, visual %.4f m (%.3fx)\n", sum_full / 5, sum_visual / 5,
              sum_full / sum_visual);
  EXPECT_LE(sum_full, 1.05 * sum_visual);
}

}  // namespace
}  // namespace viqu

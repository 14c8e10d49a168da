// Dynamic objects (issue 7) on the shipped dynamic scenarios, live, with the truth of the
// simulator: each test runs one scenario with the methods it compares (sync mapping, so every
// figure is deterministic) and checks all of its figures on those runs. The bounds sit near the
// figures measured on the landed code (in the comments) with about 2x margin on the error (docs/MEASURED.md,
// "Dynamic objects"); where issue 7's target is tighter than that and met, the target is the
// bound. Targets not met (standing_people) are reported in the README, not hidden in a bound.
// The runs use slam.mode visual_dynamic: the dynamic stage on vision alone. In mode full the leg
// odometry's motion prior already keeps walking_people's no-removal baseline at 3.2 mm (from
// 50 mm), which would hide what the dynamic stage does; WalkingPeople also runs full once.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"
#include "slam/eval/trajectory.h"
#include "slam/eval/trajectory_error.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

struct DynamicRun {
  YAML::Node m;  // metrics.json
  fs::path dir;  // the run folder
  double ate_m() const { return m["ate"]["rmse_m"].as<double>(); }
  double pct() const { return m["ate"]["rmse_pct_path"].as<double>(); }
  int lost() const { return m["tracking"]["lost_frames"].as<int>(); }
  double dyn(const char* key) const { return m["dynamic"][key].IsNull() ? -1.0 : m["dynamic"][key].as<double>(); }
};

// `seed` 0 keeps the scenario's own seed.
DynamicRun RunMethod(const std::string& scenario, const std::string& method, const std::string& mode = "visual_dynamic",
                     int seed = 0) {
  std::vector<std::string> sets = {"slam.dynamic.method=" + method, "slam.mode=" + mode};
  if (seed != 0) sets.push_back("seed=" + std::to_string(seed));
  const Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/" + scenario + ".yaml", sets);
  const fs::path dir = fs::temp_directory_path() /
                       ("viqu_dynamic_" + scenario + "_" + method + "_" + mode + (seed != 0 ? "_seed" + std::to_string(seed) : ""));
  fs::remove_all(dir);
  runner::RunOptions opt;
  opt.out_dir = dir.string();
  EXPECT_EQ(runner::RunScenario(s, opt), 0);
  EXPECT_TRUE(fs::exists(dir / "dynamic.csv"));
  DynamicRun r{YAML::LoadFile((dir / "metrics.json").string()), dir};
  std::printf("%s %s %-9s ATE %.4f m (%.3f%% of path), %d lost; precision %.3f recall %.3f latency median %.2f s "
              "max %.2f s; kept on static movables %.3f, dropped on moving %.3f; dynamic stage %.2f ms median\n",
              scenario.c_str(), mode.c_str(), method.c_str(), r.ate_m(), r.pct(), r.lost(), r.dyn("precision"), r.dyn("recall"),
              r.dyn("latency_s_median"), r.dyn("latency_s_max"), r.dyn("kept_on_static_movables"),
              r.dyn("dropped_on_moving"), r.m["timing"]["dynamic_ms_median"].as<double>());
  return r;
}

// Time of the run's first lost frame (tracking.csv), infinity when none was lost.
double FirstLostS(const DynamicRun& r) {
  std::ifstream csv(r.dir / "tracking.csv");
  std::string line;
  std::getline(csv, line);  // header: t_s,status,...
  while (std::getline(csv, line)) {
    const size_t comma = line.find(',');
    if (line.compare(comma + 1, 5, "lost,") == 0) return std::stod(line.substr(0, comma));
  }
  return std::numeric_limits<double>::infinity();
}

// ATE (m) over the poses before `t_s`, aligned on those alone.
double AteBefore(const DynamicRun& r, double t_s) {
  eval::Trajectory est, gt;
  for (const StampedPose& p : eval::ReadTumTrajectory((r.dir / "trajectory_est.txt").string())) {
    if (p.t_ns * 1e-9 < t_s) est.push_back(p);
  }
  for (const StampedPose& p : eval::ReadTumTrajectory((r.dir / "trajectory_gt.txt").string())) {
    if (p.t_ns * 1e-9 < t_s) gt.push_back(p);
  }
  return eval::ComputeAte(est, gt).ate.rmse;
}

// Detection against truth over object-frames with at least 20 features.
void ExpectDetection(const DynamicRun& r, double min_precision, double min_recall, double max_latency_median_s) {
  EXPECT_GE(r.dyn("precision"), min_precision);
  EXPECT_GE(r.dyn("recall"), min_recall);
  EXPECT_GE(r.dyn("latency_s_median"), 0.0);  // every scored object was detected at least once
  EXPECT_LE(r.dyn("latency_s_median"), max_latency_median_s);
}

// At seed 1, not the scenario's 7: since session 33 (the fusion check, docs/MEASURED.md "Point fusion,
// session 33") the no-removal baseline tracks at 3.1 mm at seed 7, so no removal can beat it
// there; at seeds 1, 2 and 3 it still fails (54.5, 45.0, 53.0 mm), as it did at 7 before (47.5).
TEST(DynamicScenarios, WalkingPeople) {
  const DynamicRun none = RunMethod("walking_people", "none", "visual_dynamic", 1);
  const DynamicRun adaptive = RunMethod("walking_people", "adaptive", "visual_dynamic", 1);
  std::printf("walking_people: adaptive / none ATE = %.3f\n", adaptive.ate_m() / none.ate_m());
  // Measured 0.080 (3.8 / 47.5 mm) since session 16 rendered depth for the detector model's mask
  // growth order (0.070, 3.5 / 50.2 mm, before); target 0.2. At seed 1 (session 33): 0.062 (3.4 /
  // 54.5 mm), precision 0.999, recall 0.980, median latency 0.10 s.
  EXPECT_LE(adaptive.ate_m(), 0.15 * none.ate_m());
  EXPECT_LE(adaptive.pct(), 0.12);                    // measured 0.06% of path; target 0.2%
  EXPECT_EQ(adaptive.lost(), 0);
  // Measured precision 0.999, recall 0.936, median latency 0.40 s (targets 0.95, 0.90, 0.5 s),
  // recall 0.961 since session 20, 0.979 (0.10 s) since session 22 (the mask's look);
  // recall 0.951 before session 16 dated a stop by the first look that sees it (the 1 s pauses
  // of these walkers now end as their hold does). Bound: 2.4x the share missed.
  ExpectDetection(adaptive, 0.95, 0.95, 0.8);
  EXPECT_EQ(none.dyn("dropped_on_moving"), 0.0);  // the baseline keeps everything
  // Mode full (leg odometry + IMU fused, issue 8): measured 3.9 mm, 0.078x the no-removal
  // baseline (issue 8's target on walking_people: 0.7x vision alone). Against adaptive on vision
  // alone it measured 0.76x (2.9 / 3.8 mm) before session 8's change to adaptive and 1.15x
  // (3.9 / 3.4 mm) after it: issue 8's "full <= visual + 5%" is missed here against
  // visual_dynamic (docs/MEASURED.md, issue 8's figures); the bound below catches a further slide.
  const DynamicRun full = RunMethod("walking_people", "adaptive", "full", 1);
  std::printf("walking_people: full / none ATE = %.3f, full / visual_dynamic adaptive = %.3f\n",
              full.ate_m() / none.ate_m(), full.ate_m() / adaptive.ate_m());
  EXPECT_LE(full.ate_m(), 0.13 * none.ate_m());
  EXPECT_LE(full.ate_m(), 1.4 * adaptive.ate_m());
  EXPECT_EQ(full.lost(), 0);
}

TEST(DynamicScenarios, PushedBox) {
  const DynamicRun none = RunMethod("pushed_box", "none");
  const DynamicRun adaptive = RunMethod("pushed_box", "adaptive");
  std::printf("pushed_box: adaptive / none ATE = %.4f\n", adaptive.ate_m() / none.ate_m());
  EXPECT_GE(none.pct(), 5 * 0.04);  // the baseline degrades: 5x static_room's 0.04% of path
  EXPECT_LE(adaptive.ate_m(), 0.02 * none.ate_m());  // measured 0.0055 (4.0 / 729.7 mm); target 0.25
  EXPECT_EQ(adaptive.lost(), 0);
  // Measured 1.000, 0.975, 0.50 s (precision 0.963 before session 16: the crate was held up to
  // 1 s longer after it stopped).
  ExpectDetection(adaptive, 0.97, 0.95, 1.0);
}

TEST(DynamicScenarios, StandingPeople) {
  const DynamicRun semantic = RunMethod("standing_people", "semantic");
  const DynamicRun adaptive = RunMethod("standing_people", "adaptive");
  std::printf("standing_people: adaptive / semantic ATE = %.3f\n", adaptive.ate_m() / semantic.ate_m());
  // Measured 1.01 (2.9 / 2.9 mm), 1.17 (2.8 / 2.4 mm) since session 16, 0.93 (2.2 / 2.4 mm) since
  // session 22: issue 7's target (0.8) is not met, see the README.
  EXPECT_LE(adaptive.ate_m(), 2.0 * semantic.ate_m());
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.95);  // measured 1.000; target 0.90
  // Measured 0.692, 0.731 since session 19 (the frame of the decision drops it too), 0.795 since
  // session 20 (looks a quarter second old), 0.851 since session 21 (dropped at the first look
  // that sees motion, drop_frames 1), 0.948 since session 22 (the mask's look drops a walker on its
  // first frame of motion); target 0.95. Bound: 1.7x the share not dropped.
  EXPECT_GE(adaptive.dyn("dropped_on_moving"), 0.91);
  EXPECT_EQ(adaptive.lost(), 0);
  // Measured 1.000, 0.769, 0.25 s; recall 0.818 since session 20, 0.858 (0.20 s) since session 21,
  // 0.953 (0.05 s) since session 22 (target 0.90; the walkers' first frames, at their start time,
  // show no motion: the 7 misses). Bound: 1.5x the share missed.
  ExpectDetection(adaptive, 0.95, 0.93, 0.5);
  EXPECT_EQ(semantic.dyn("kept_on_static_movables"), 0.0);  // semantic drops every person
}

// The same corridor of people on a plain checker floor with no walls: the people are nearly all
// the texture, so removing them by category loses the track.
TEST(DynamicScenarios, StandingCrowd) {
  const DynamicRun semantic = RunMethod("standing_crowd", "semantic");
  const DynamicRun adaptive = RunMethod("standing_crowd", "adaptive");
  std::printf("standing_crowd: adaptive / semantic ATE = %.3f\n", adaptive.ate_m() / semantic.ate_m());
  EXPECT_GE(semantic.lost(), 300);                            // measured 710 of 801 frames lost, 703 since session 25
  // The run's one loss: at 32.9 s the last walkers have left and the bare checker floor gives
  // about 50 features a frame (none dropped by the stage). Until session 25 the 20 lost frames
  // were dead-reckoned at constant velocity and the new segment's landing decided the whole run's
  // ATE (43.2, 95.2, 237.7, 78.6 mm over sessions with every pose before the loss within a few mm);
  // since then they are carried frame to frame and the segment starts as soon as a frame is
  // carried by 30 points (7 lost frames), so the whole run is bounded too. Since session 27 a frame
  // needs 30 map points among its inliers (the last frame's temporary points no longer count):
  // 11 lost frames from 32.70 s, 13.7 mm.
  const double first_lost_s = FirstLostS(adaptive);
  const double ate_before_loss = AteBefore(adaptive, first_lost_s);
  std::printf("standing_crowd adaptive: first lost frame at %.2f s, ATE before it %.4f m\n", first_lost_s, ate_before_loss);
  EXPECT_GE(first_lost_s, 30.0);                              // measured 32.85 s, 32.90 s since session 22
  EXPECT_LE(ate_before_loss, 0.012);                          // measured 12.4 mm, 12.9 mm since session 13,
                                                              // 5.9 mm since session 21, 10.6 mm since
                                                              // session 22 (a jolted frame at 16.8 s)
  EXPECT_LE(adaptive.ate_m(), 0.040);                         // measured 20.6 mm since session 25, 13.7 mm
                                                              // since session 27
  EXPECT_LE(adaptive.ate_m(), 0.045 * semantic.ate_m());      // measured 0.099 (95.2 / 963.4 mm), 0.245 (237.7 /
                                                              // 971.0 mm) since session 13 or earlier, 20.9 mm
                                                              // since session 21, 0.081 (78.6 / 971.0 mm)
                                                              // since session 22, 0.023 (20.6 / 905.3 mm)
                                                              // since session 25; target 0.8
  EXPECT_LE(adaptive.lost(), 15);                             // measured 20, 7 since session 25, 11 since
                                                              // session 27
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.95);   // measured 1.00; target 0.90
  EXPECT_GE(adaptive.dyn("dropped_on_moving"), 0.92);         // measured 0.79, 0.84 since session 19, 0.884
                                                              // since session 21, 0.954 since session 22;
                                                              // target 0.95; bound 1.7x the share not dropped
  // Measured 1.000, 0.859 (target 0.90), 0.20 s; 0.973, 0.896, 0.15 s since session 21 (single
  // frames dropped at a first look of motion that the next look does not confirm); 0.987, 0.963,
  // 0.05 s since session 22. Bound: 1.5x the share missed.
  ExpectDetection(adaptive, 0.95, 0.945, 0.5);
}

// Two people zigzag 1.3-1.8 m ahead, pausing 1 s at each turn. Released at the end of a pause,
// carol walked on for 1.5 s unjudged (her leg features, mostly background in their patches at
// 2 m, do not match between frames): recall 0.854, dropped on moving 0.888 before session 19's
// rule that looks which cannot be judged soon after a release count as motion.
TEST(DynamicScenarios, WalkingPeopleFar) {
  const DynamicRun adaptive = RunMethod("walking_people_far", "adaptive");
  EXPECT_EQ(adaptive.lost(), 0);
  EXPECT_LE(adaptive.pct(), 0.12);                           // measured 3.3 mm
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.93);  // measured 0.970
  EXPECT_GE(adaptive.dyn("dropped_on_moving"), 0.95);        // measured 0.944 (0.888 before), 0.976 since
                                                             // session 22 (the mask's look)
  ExpectDetection(adaptive, 0.95, 0.94, 0.8);                // measured 0.998, 0.944 (0.854 before), 0.35 s;
                                                             // 0.998, 0.970, 0.05 s since session 22
}

TEST(DynamicScenarios, StandingThenWalking) {
  const DynamicRun adaptive = RunMethod("standing_then_walking", "adaptive");
  EXPECT_EQ(adaptive.lost(), 0);
  EXPECT_LE(adaptive.pct(), 0.12);                           // measured 0.061% (none: 0.17%)
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.95);  // measured 0.998
  // Measured 1.000, 0.972, 0.10 s. At seed 2 precision was 0.878 (erin held 0.5 s after the
  // truth's second after her stop), 0.986 since session 16; seeds 3-6: 1.000.
  ExpectDetection(adaptive, 0.95, 0.93, 0.5);
}

}  // namespace
}  // namespace viqu

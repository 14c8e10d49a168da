// Dynamic objects (issue 7) on the shipped dynamic scenarios, live, with the truth of the
// simulator: each test runs one scenario with the methods it compares (sync mapping, so every
// figure is deterministic) and checks all of its figures on those runs. The bounds sit near the
// figures measured on the landed code (in the comments) with about 2x margin on the error (README,
// "Dynamic objects"); where issue 7's target is tighter than that and met, the target is the
// bound. Targets not met (standing_people) are reported in the README, not hidden in a bound.
// The runs use slam.mode visual_dynamic: the dynamic stage on vision alone. In mode full the leg
// odometry's motion prior already keeps walking_people's no-removal baseline at 3.2 mm (from
// 50 mm), which would hide what the dynamic stage does; WalkingPeople also runs full once.
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

struct DynamicRun {
  YAML::Node m;  // metrics.json
  double ate_m() const { return m["ate"]["rmse_m"].as<double>(); }
  double pct() const { return m["ate"]["rmse_pct_path"].as<double>(); }
  int lost() const { return m["tracking"]["lost_frames"].as<int>(); }
  double dyn(const char* key) const { return m["dynamic"][key].IsNull() ? -1.0 : m["dynamic"][key].as<double>(); }
};

DynamicRun RunMethod(const std::string& scenario, const std::string& method, const std::string& mode = "visual_dynamic") {
  const Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/" + scenario + ".yaml",
                                  {"slam.dynamic.method=" + method, "slam.mode=" + mode});
  const fs::path dir = fs::temp_directory_path() / ("viqu_dynamic_" + scenario + "_" + method + "_" + mode);
  fs::remove_all(dir);
  runner::RunOptions opt;
  opt.out_dir = dir.string();
  EXPECT_EQ(runner::RunScenario(s, opt), 0);
  EXPECT_TRUE(fs::exists(dir / "dynamic.csv"));
  DynamicRun r{YAML::LoadFile((dir / "metrics.json").string())};
  std::printf("%s %s %-9s ATE %.4f m (%.3f%% of path), %d lost; precision %.3f recall %.3f latency median %.2f s "
              "max %.2f s; kept on static movables %.3f, dropped on moving %.3f; dynamic stage %.2f ms median\n",
              scenario.c_str(), mode.c_str(), method.c_str(), r.ate_m(), r.pct(), r.lost(), r.dyn("precision"), r.dyn("recall"),
              r.dyn("latency_s_median"), r.dyn("latency_s_max"), r.dyn("kept_on_static_movables"),
              r.dyn("dropped_on_moving"), r.m["timing"]["dynamic_ms_median"].as<double>());
  return r;
}

// Detection against truth over object-frames with at least 20 features.
void ExpectDetection(const DynamicRun& r, double min_precision, double min_recall, double max_latency_median_s) {
  EXPECT_GE(r.dyn("precision"), min_precision);
  EXPECT_GE(r.dyn("recall"), min_recall);
  EXPECT_GE(r.dyn("latency_s_median"), 0.0);  // every scored object was detected at least once
  EXPECT_LE(r.dyn("latency_s_median"), max_latency_median_s);
}

TEST(DynamicScenarios, WalkingPeople) {
  const DynamicRun none = RunMethod("walking_people", "none");
  const DynamicRun adaptive = RunMethod("walking_people", "adaptive");
  std::printf("walking_people: adaptive / none ATE = %.3f\n", adaptive.ate_m() / none.ate_m());
  EXPECT_LE(adaptive.ate_m(), 0.15 * none.ate_m());  // measured 0.076 (3.8 / 50.2 mm); target 0.2
  EXPECT_LE(adaptive.pct(), 0.12);                    // measured 0.059% of path; target 0.2%
  EXPECT_EQ(adaptive.lost(), 0);
  // Measured precision 0.999, recall 0.913, median latency 0.55 s (targets 0.95, 0.90, 0.5 s).
  ExpectDetection(adaptive, 0.95, 0.83, 1.0);
  EXPECT_EQ(none.dyn("dropped_on_moving"), 0.0);  // the baseline keeps everything
  // Mode full (leg odometry + IMU fused, issue 8): measured 2.9 mm, 0.058x the no-removal
  // baseline (issue 8's target on walking_people: 0.7x vision alone) and below adaptive on
  // vision alone (3.8 mm).
  const DynamicRun full = RunMethod("walking_people", "adaptive", "full");
  std::printf("walking_people: full / none ATE = %.3f, full / visual_dynamic adaptive = %.3f\n",
              full.ate_m() / none.ate_m(), full.ate_m() / adaptive.ate_m());
  EXPECT_LE(full.ate_m(), 0.13 * none.ate_m());
  EXPECT_LE(full.ate_m(), 1.05 * adaptive.ate_m());
  EXPECT_EQ(full.lost(), 0);
}

TEST(DynamicScenarios, PushedBox) {
  const DynamicRun none = RunMethod("pushed_box", "none");
  const DynamicRun adaptive = RunMethod("pushed_box", "adaptive");
  std::printf("pushed_box: adaptive / none ATE = %.4f\n", adaptive.ate_m() / none.ate_m());
  EXPECT_GE(none.pct(), 5 * 0.04);  // the baseline degrades: 5x static_room's 0.04% of path
  EXPECT_LE(adaptive.ate_m(), 0.02 * none.ate_m());  // measured 0.0055 (4.0 / 729.7 mm); target 0.25
  EXPECT_EQ(adaptive.lost(), 0);
  ExpectDetection(adaptive, 0.92, 0.95, 1.0);  // measured 0.963, 0.975, 0.50 s
}

TEST(DynamicScenarios, StandingPeople) {
  const DynamicRun semantic = RunMethod("standing_people", "semantic");
  const DynamicRun adaptive = RunMethod("standing_people", "adaptive");
  std::printf("standing_people: adaptive / semantic ATE = %.3f\n", adaptive.ate_m() / semantic.ate_m());
  // Measured 1.49 (3.6 / 2.4 mm): issue 7's target (0.8) is not met, see the README.
  EXPECT_LE(adaptive.ate_m(), 2.0 * semantic.ate_m());
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.95);  // measured 1.000; target 0.90
  EXPECT_GE(adaptive.dyn("dropped_on_moving"), 0.2);         // measured 0.360; target 0.95, not met
  EXPECT_EQ(adaptive.lost(), 0);
  ExpectDetection(adaptive, 0.9, 0.25, 1.0);  // measured 1.000, 0.453 (target 0.90, not met), 0.42 s
  EXPECT_EQ(semantic.dyn("kept_on_static_movables"), 0.0);  // semantic drops every person
}

// The same corridor of people on a plain checker floor with no walls: the people are nearly all
// the texture, so removing them by category loses the track.
TEST(DynamicScenarios, StandingCrowd) {
  const DynamicRun semantic = RunMethod("standing_crowd", "semantic");
  const DynamicRun adaptive = RunMethod("standing_crowd", "adaptive");
  std::printf("standing_crowd: adaptive / semantic ATE = %.3f\n", adaptive.ate_m() / semantic.ate_m());
  EXPECT_GE(semantic.lost(), 300);                            // measured 659 of 801 frames lost
  EXPECT_LE(adaptive.ate_m(), 0.12 * semantic.ate_m());       // measured 0.059 (43.2 / 735.5 mm); target 0.8
  EXPECT_LE(adaptive.lost(), 40);                             // measured 20
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.90);   // measured 0.98; target 0.90
  EXPECT_GE(adaptive.dyn("dropped_on_moving"), 0.45);         // measured 0.73; target 0.95, not met
  ExpectDetection(adaptive, 0.6, 0.6, 0.5);                   // measured 0.816, 0.816, 0.25 s
}

TEST(DynamicScenarios, StandingThenWalking) {
  const DynamicRun adaptive = RunMethod("standing_then_walking", "adaptive");
  EXPECT_EQ(adaptive.lost(), 0);
  EXPECT_LE(adaptive.pct(), 0.12);                           // measured 0.061% (none: 0.17%)
  EXPECT_GE(adaptive.dyn("kept_on_static_movables"), 0.95);  // measured 0.991
  ExpectDetection(adaptive, 0.85, 0.93, 0.5);                // measured 0.933, 0.972, 0.10 s
}

}  // namespace
}  // namespace viqu

// A run is deterministic given its seed: same seed, same ground truth and the same image bytes;
// another seed changes the sensor noise.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "runner/run_scenario.h"
#include "short_scenario.h"
#include "read_all.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

using testing::ReadAll;

Scenario ShortScenario(uint64_t seed) { return testing::ShortWalkerScenario("determinism", seed); }

fs::path RunInto(const Scenario& s, const std::string& tag, bool slam = false, bool sequential = false) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_determinism_" + tag);
  fs::remove_all(dir);
  runner::RunOptions opt;
  opt.out_dir = dir.string();
  opt.slam = slam;
  opt.sequential = sequential;
  opt.record = true;
  EXPECT_EQ(runner::RunScenario(s, opt), 0);
  return dir;
}

TEST(Determinism, SameSeedSameBytesOtherSeedOtherNoise) {
  const fs::path a = RunInto(ShortScenario(5), "a");
  const fs::path b = RunInto(ShortScenario(5), "b");
  const fs::path c = RunInto(ShortScenario(6), "c");
  EXPECT_EQ(ReadAll(a / "trajectory_gt.txt"), ReadAll(b / "trajectory_gt.txt"));
  const fs::path cam0 = fs::path("dataset") / "mav0" / "cam0" / "data";
  int images = 0, differing_other_seed = 0;
  for (const auto& entry : fs::directory_iterator(a / cam0)) {
    const fs::path name = entry.path().filename();
    EXPECT_EQ(ReadAll(entry.path()), ReadAll(b / cam0 / name)) << name;
    differing_other_seed += ReadAll(entry.path()) != ReadAll(c / cam0 / name);
    ++images;
  }
  EXPECT_EQ(images, 21);  // 1 s at 20 Hz, frames at t = 0 and t = 1 s included
  EXPECT_EQ(differing_other_seed, images);
  const std::string imu = "dataset/mav0/imu0/data.csv";
  EXPECT_EQ(ReadAll(a / imu), ReadAll(b / imu));
  EXPECT_NE(ReadAll(a / imu), ReadAll(c / imu));
  for (const auto& d : {a, b, c}) fs::remove_all(d);
}

// The estimator stage runs on its own thread beside the renderer (runner/ordered_worker.h); the
// outputs must be those of the sequential loop, byte for byte, also when the robot steers by the
// estimate (the fixed one-frame delay of runner/run_scenario.cc), and with leg odometry fused.
TEST(Determinism, OverlappedStagesGiveTheSequentialLoopsBytes) {
  Scenario s = ShortScenario(7);
  s.duration_s = 3.0;
  s.robot.command.velocity.clear();
  s.robot.command.waypoints = {{0.25, 0.0}, {0.25, 0.25}};
  s.robot.command.follow = "estimate";
  const fs::path seq = RunInto(s, "seq", true, true);
  const fs::path ovl = RunInto(s, "ovl", true, false);
  for (const char* f : {"trajectory_gt.txt", "trajectory_est.txt", "trajectory_lo.txt", "lo.csv", "dynamic.csv",
                        "slip.csv", "contact.csv", "dataset/mav0/imu0/data.csv", "dataset/mav0/cam0/data.csv"}) {
    const std::string a = ReadAll(seq / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_EQ(a, ReadAll(ovl / f)) << f;
  }
  // tracking.csv without its two timing columns (track_ms, dynamic_ms).
  auto without_timing = [](const std::string& csv) {
    std::stringstream in(csv), out;
    std::string line;
    while (std::getline(in, line)) {
      std::stringstream fields(line);
      std::string field;
      for (int i = 0; std::getline(fields, field, ','); ++i) {
        if (i != 6 && i != 8) out << field << ',';
      }
      out << '\n';
    }
    return out.str();
  };
  const std::string tracking = without_timing(ReadAll(seq / "tracking.csv"));
  EXPECT_EQ(std::count(tracking.begin(), tracking.end(), '\n'), 62);  // header + 61 frames in 3 s at 20 Hz
  EXPECT_EQ(tracking, without_timing(ReadAll(ovl / "tracking.csv")));
  // The robot steered by the estimate and moved towards the first waypoint.
  std::stringstream gt(ReadAll(seq / "trajectory_gt.txt"));
  std::string line, last;
  while (std::getline(gt, line)) last = line;
  double t, x, y;
  std::stringstream(last) >> t >> x >> y;
  EXPECT_GT(x, 0.05) << last;
  for (const auto& d : {seq, ovl}) fs::remove_all(d);
}

}  // namespace
}  // namespace viqu

// The run loop's observer (runner/run_observer.h), which the viewer uses: it sees every camera
// frame in order with the simulation, the ground truth and the estimate of the same instant; it
// changes no output; and asking to stop ends the run with the folder marked incomplete.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/run_folder.h"
#include "runner/run_scenario.h"
#include "short_scenario.h"
#include "runner/slam_run.h"
#include "sim/world.h"
#include "read_all.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

using testing::ReadAll;

Scenario ShortScenario() { return testing::ShortWalkerScenario("observer", 11); }

// Checks each frame against the simulation it comes with; can ask to stop after some frames.
class CheckingObserver : public runner::RunObserver {
 public:
  explicit CheckingObserver(int64_t stop_after = -1) : stop_after_(stop_after) {}

  bool OnFrame(const runner::ObservedFrame& f) override {
    EXPECT_EQ(f.index, frames_);
    EXPECT_EQ(ends_, 0);
    ++frames_;
    // The world, the frame, the ground truth and the estimate all belong to the frame's time.
    EXPECT_NEAR(f.world->data()->time, f.t_s, 1e-9);
    EXPECT_EQ(f.frame->t_ns, std::llround(f.t_s * 1e9));
    EXPECT_FALSE(f.frame->left_rgb.empty());
    EXPECT_EQ(f.ground_truth->size(), static_cast<size_t>(frames_));
    const Eigen::Vector3d p_cam = f.world->GroundTruth().T_w_cam.p_w_x;
    EXPECT_NEAR((f.ground_truth->back().p_w_x - p_cam).norm(), 0, 1e-12);
    EXPECT_NE(f.track, nullptr);
    EXPECT_NE(f.slam, nullptr);
    if (f.track && f.slam) {
      EXPECT_EQ(f.track->t_ns, f.frame->t_ns);
      EXPECT_EQ(f.slam->estimate().size(), static_cast<size_t>(frames_));
      // slam.mode full (the default): the leg-odometry path comes with it, a pose per frame.
      EXPECT_NE(f.leg_odometry, nullptr);
      if (f.leg_odometry) {
        EXPECT_EQ(f.leg_odometry->size(), static_cast<size_t>(frames_));
      }
      max_error_m_ = std::max(max_error_m_, (f.track->T_w_c.translation() - p_cam).norm());
      map_points_ = f.slam->system().MapPoints().size();
    }
    return stop_after_ < 0 || frames_ <= stop_after_;
  }
  void OnRunEnd(const runner::ObservedFrame& last) override {
    ++ends_;
    last_index_ = last.index;
    EXPECT_NE(last.world, nullptr);
    EXPECT_EQ(last.frame, nullptr);
    EXPECT_EQ(last.track, nullptr);
  }

  int64_t stop_after_;
  int64_t frames_ = 0;
  int ends_ = 0;
  int64_t last_index_ = -1;
  double max_error_m_ = 0;
  size_t map_points_ = 0;
};

fs::path RunInto(const std::string& tag, runner::RunObserver* observer, int expected_exit = 0) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_observer_" + tag);
  fs::remove_all(dir);
  runner::RunOptions opt;
  opt.out_dir = dir.string();
  EXPECT_EQ(runner::RunScenario(ShortScenario(), opt, observer), expected_exit);
  return dir;
}

TEST(RunObserver, SeesEveryFrameOfTheSameInstantAndChangesNoOutput) {
  CheckingObserver seen;
  const fs::path watched = RunInto("watched", &seen);
  const fs::path plain = RunInto("plain", nullptr);
  EXPECT_EQ(seen.frames_, 21);  // 1 s at 20 Hz, frames at 0 and 1 s included
  EXPECT_EQ(seen.ends_, 1);
  EXPECT_EQ(seen.last_index_, 20);
  std::printf("observer: largest position error of the estimate it saw %.2f mm, %zu map points at the end\n",
              1e3 * seen.max_error_m_, seen.map_points_);
  EXPECT_LT(seen.max_error_m_, 0.004);  // the estimate it sees is the run's: measured 1.9 mm, 2x margin
  EXPECT_GT(seen.map_points_, 700u);  // measured 1425
  EXPECT_TRUE(IsCompleteRunFolder(watched.string()));
  for (const char* f : {"trajectory_gt.txt", "trajectory_est.txt", "trajectory_lo.txt", "dynamic.csv"}) {
    EXPECT_EQ(ReadAll(watched / f), ReadAll(plain / f)) << f;
    EXPECT_FALSE(ReadAll(plain / f).empty()) << f;
  }
}

TEST(RunObserver, AskingToStopEndsTheRunMarkedIncomplete) {
  CheckingObserver stopper(5);  // false after the 6th frame
  const fs::path dir = RunInto("stopped", &stopper);
  EXPECT_EQ(stopper.frames_, 6);
  EXPECT_EQ(stopper.ends_, 1);
  EXPECT_EQ(stopper.last_index_, 5);
  std::string why;
  EXPECT_FALSE(IsCompleteRunFolder(dir.string(), &why));
  EXPECT_TRUE(fs::exists(dir / kRunIncompleteMarker));
  EXPECT_NE(ReadAll(dir / kRunIncompleteMarker).find("viewer closed"), std::string::npos);
  // The outputs hold the frames up to the stop, every one of them whole.
  std::istringstream gt(ReadAll(dir / "trajectory_gt.txt"));
  int lines = 0;
  for (std::string line; std::getline(gt, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, 6);
}

}  // namespace
}  // namespace viqu

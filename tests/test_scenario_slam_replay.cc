// Offline SLAM replays a recorded run exactly (issue 3, item 6): a scenario is run live with SLAM
// (sync mapping) while recording it, then `viqu slam` replays the recording; in the project's
// own format (stereo) and in TUM RGB-D (rgbd mode) the replayed trajectory equals the live one.
// The EuRoC reader, which rectifies and converts images on the way in, and real-time mapping
// track the same recording with an ATE close to the live run's.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "apps/cli.h"
#include "apps/run_scenario.h"
#include "apps/slam_command.h"
#include "common/errors.h"
#include "scenario/scenario_loader.h"
#include "slam/eval/trajectory.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

constexpr double kSeconds = 8;  // 160 frames: initialisation, keyframes, local BA

Scenario ShortRoom(const std::string& settings_file) {
  Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml", {});
  s.duration_s = kSeconds;
  s.sensors.camera.depth = true;
  s.slam.config = settings_file;
  return s;
}

fs::path Fresh(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_slam_replay_" + tag);
  fs::remove_all(dir);
  return dir;
}

void ExpectSameTrajectory(const fs::path& a, const fs::path& b) {
  const eval::Trajectory ta = eval::ReadTumTrajectory(a.string());
  const eval::Trajectory tb = eval::ReadTumTrajectory(b.string());
  ASSERT_EQ(ta.size(), tb.size());
  ASSERT_GT(ta.size(), 100u);
  double worst_m = 0, worst_rad = 0;
  for (size_t i = 0; i < ta.size(); ++i) {
    ASSERT_EQ(ta[i].t_ns, tb[i].t_ns);
    worst_m = std::max(worst_m, (ta[i].p_w_x - tb[i].p_w_x).norm());
    worst_rad = std::max(worst_rad, ta[i].q_w_x.angularDistance(tb[i].q_w_x));
  }
  EXPECT_LT(worst_m, 1e-6);
  EXPECT_LT(worst_rad, 1e-6);
}

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

double Ate(const fs::path& run) { return YAML::LoadFile((run / "metrics.json").string())["ate"]["rmse_m"].as<double>(); }

TEST(SlamReplay, ViquAndEurocFormatsReplayTheLiveStereoRun) {
  const fs::path live = Fresh("stereo_live");
  app::RunOptions opt;
  opt.out_dir = live.string();
  opt.record = true;
  ASSERT_EQ(app::RunScenario(ShortRoom(""), opt), 0);

  app::SlamArgs args;
  args.dataset_dir = live.string();
  args.format = "viqu";
  args.out_dir = Fresh("stereo_viqu").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  ExpectSameTrajectory(live / "trajectory_est.txt", fs::path(args.out_dir) / "trajectory_est.txt");
  // Same statuses and counts frame by frame (the timing column aside).
  auto strip_time = [](std::string csv) {
    std::string out;
    size_t pos = 0;
    while (pos < csv.size()) {
      const size_t end = csv.find('\n', pos);
      const std::string line = csv.substr(pos, end - pos);
      out += line.substr(0, line.rfind(',')) + "\n";
      pos = end == std::string::npos ? csv.size() : end + 1;
    }
    return out;
  };
  EXPECT_EQ(strip_time(ReadAll(live / "tracking.csv")), strip_time(ReadAll(fs::path(args.out_dir) / "tracking.csv")));

  args.dataset_dir = (live / "dataset").string();
  args.format = "euroc";
  args.out_dir = Fresh("stereo_euroc").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const YAML::Node m = YAML::LoadFile(args.out_dir + "/metrics.json");
  EXPECT_EQ(m["tracking"]["lost_frames"].as<int>(), 0);
  std::printf("ATE live %.4f m, EuRoC replay %.4f m\n", Ate(live), Ate(args.out_dir));
  EXPECT_LT(Ate(args.out_dir), 2 * Ate(live) + 0.002);

  // Real-time mode (mapping on its own thread) on the same recording: not bit-reproducible, but
  // as good.
  const fs::path cfg = Fresh("realtime_config.yaml");
  std::ofstream(cfg) << "mapping: {mode: realtime}\n";
  args.dataset_dir = live.string();
  args.format = "viqu";
  args.config = cfg.string();
  args.out_dir = Fresh("stereo_realtime").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const YAML::Node rt = YAML::LoadFile(args.out_dir + "/metrics.json");
  EXPECT_EQ(rt["slam"]["mapping_mode"].as<std::string>(), "realtime");
  EXPECT_EQ(rt["tracking"]["lost_frames"].as<int>(), 0);
  EXPECT_GT(rt["timing"]["local_ba_count"].as<int>(), 0);
  std::printf("ATE live %.4f m, real-time mapping replay %.4f m\n", Ate(live), Ate(args.out_dir));
  EXPECT_LT(Ate(args.out_dir), 2 * Ate(live) + 0.002);
}

TEST(SlamReplay, TumFormatReplaysTheLiveRgbdRun) {
  const fs::path cfg_dir = Fresh("rgbd_config");
  fs::create_directories(cfg_dir);
  const fs::path cfg = cfg_dir / "rgbd.yaml";
  std::ofstream(cfg) << "input: rgbd\n";
  const fs::path live = Fresh("rgbd_live");
  app::RunOptions opt;
  opt.out_dir = live.string();
  opt.record_tum = true;
  ASSERT_EQ(app::RunScenario(ShortRoom(cfg.string()), opt), 0);
  const YAML::Node m = YAML::LoadFile((live / "metrics.json").string());
  EXPECT_EQ(m["slam"]["input"].as<std::string>(), "rgbd");
  EXPECT_EQ(m["tracking"]["lost_frames"].as<int>(), 0);

  app::SlamArgs args;
  args.dataset_dir = (live / "dataset_tum").string();
  args.format = "tum";
  args.config = cfg.string();
  args.out_dir = Fresh("rgbd_tum").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  ExpectSameTrajectory(live / "trajectory_est.txt", fs::path(args.out_dir) / "trajectory_est.txt");
}

TEST(SlamReplay, EmptyOrMissingDatasetIsBadInput) {
  const fs::path empty = Fresh("empty");
  fs::create_directories(empty);
  app::SlamArgs args;
  args.dataset_dir = empty.string();
  args.out_dir = Fresh("empty_out").string();
  for (const char* format : {"viqu", "euroc", "tum"}) {
    args.format = format;
    EXPECT_THROW(app::RunSlamCommand(args), InputError) << format;
  }
  EXPECT_FALSE(fs::exists(fs::path(args.out_dir) / "metrics.json"));
  EXPECT_FALSE(fs::exists(fs::path(args.out_dir) / "trajectory_est.txt"));
}

}  // namespace
}  // namespace viqu

// Offline SLAM replays a recorded run exactly (issue 3, item 6; issue 7, "offline"), with the
// dynamic-object stage on (`dynamic.method: adaptive`, the default). A short walk in the room is
// run live with SLAM (sync mapping) while a person crosses 0.7-0.9 m ahead of the robot, so that
// the dynamic stage drops features (checked: the tests cannot pass with a stage that does
// nothing); `viqu slam` then replays the recording:
//  - the project's own format (stereo, masks from seg0): the same trajectory file byte for byte,
//    the same tracking.csv, and dynamic.csv and the dynamic.* metrics (precision, recall, latency)
//    exactly, truth columns included (the recording keeps the objects' truth, mav0/objects0).
//    The detector model of this run also reports wrong categories and spurious masks,
//    which seg0 must carry per frame;
//  - a live run in rgbd mode, recorded with both --record and --record-tum, replays exactly from
//    the project's format in rgbd mode (depth0 holds the live depth's 1/5000 m steps);
//  - TUM RGB-D (rgbd mode) with `--masks`: the same run's seg0 images, renamed to the TUM rgb
//    names, plus seg0/instances.csv form a masks folder of docs/MASKS.md. "--masks changes the
//    result as the same masks do live" is read as: the TUM replay with those masks gives the live
//    rgbd run's trajectory and decisions exactly; without masks it gives another trajectory (the
//    masks matter); and with the masks but `--set dynamic.method=none` it gives exactly the
//    replay without masks (masks act only through the dynamic stage). The MASKS.md format has
//    one category per id, so this run keeps the detector's categories right
//    (wrong_category_rate 0); its spurious masks (fresh ids) are expressible and stay on.
// The EuRoC reader (rectifying on the way in, masks from the same folder) and real-time mapping
// track the same recording with an ATE close to the live run's.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "apps/cli.h"
#include "runner/run_scenario.h"
#include "apps/slam_command.h"
#include "common/errors.h"
#include "runner/metric_keys.h"
#include "scenario/scenario_loader.h"
#include "slam/eval/trajectory.h"
#include "read_all.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

constexpr double kSeconds = 8;  // 160 frames: initialisation, keyframes, local BA, a person crossing twice

// One person zigzags across the robot's path (y = -1, heading +x from x = -1 at about 0.12 m/s):
// 0.8 m/s, 1.8 m per crossing (2.3 s), 0.25 m further on per crossing, so that it stays about
// 0.8 m ahead of the camera. It stands at its first waypoint until 1 s.
ObstacleConfig CrossingPerson() {
  ObstacleConfig p;
  p.name = "walker";
  p.category = "person";
  p.size_m = {1.72};
  p.path = {{-0.2, -1.9}, {0.05, -0.1}, {0.3, -1.9}, {0.55, -0.1}};
  p.speed_mps = 0.8;
  p.start_s = 1;
  p.loop = "none";
  p.yaw_deg = 90;
  return p;
}

// `mode` full fuses leg odometry + IMU: a viqu-format replay reads imu0, joints0, contact0 and
// robot.urdf and fuses them as the live run did; the TUM and EuRoC readers have no encoders, so
// the runs compared with those exactly use visual_dynamic.
Scenario ShortRoomWithPerson(const std::string& settings_file, const std::string& mode = "visual_dynamic") {
  Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml", {"slam.mode=" + mode});
  s.duration_s = kSeconds;
  s.sensors.camera.depth = true;
  s.sensors.camera.segmentation = true;
  s.slam.config = settings_file;
  s.obstacles.push_back(CrossingPerson());
  return s;
}

fs::path Fresh(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_slam_replay_" + tag);
  fs::remove_all(dir);
  return dir;
}

using testing::ReadAll;

std::vector<std::string> Split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, sep);) out.push_back(f);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

// A CSV file with a header row: the header's fields and the data rows split on commas.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  size_t Column(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return i;
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Csv ReadCsv(const fs::path& p) {
  Csv csv;
  std::ifstream in(p);
  std::string line;
  EXPECT_TRUE(std::getline(in, line)) << p;
  csv.header = Split(line, ',');
  while (std::getline(in, line)) csv.rows.push_back(Split(line, ','));
  return csv;
}

// The rows of `csv` without the named columns, one string per row.
std::vector<std::string> RowsWithout(const Csv& csv, const std::vector<std::string>& drop) {
  std::vector<bool> dropped(csv.header.size(), false);
  for (const std::string& d : drop) dropped[csv.Column(d)] = true;
  std::vector<std::string> out;
  for (const auto& row : csv.rows) {
    std::string s;
    for (size_t i = 0; i < row.size(); ++i) {
      if (i < dropped.size() && dropped[i]) continue;
      s += row[i] + ",";
    }
    out.push_back(s);
  }
  return out;
}

// The largest position (m) and rotation (rad) difference of two trajectories with equal stamps.
std::pair<double, double> WorstDifference(const fs::path& a, const fs::path& b) {
  const eval::Trajectory ta = eval::ReadTumTrajectory(a.string());
  const eval::Trajectory tb = eval::ReadTumTrajectory(b.string());
  EXPECT_EQ(ta.size(), tb.size());
  EXPECT_GT(ta.size(), 100u);
  double worst_m = 0, worst_rad = 0;
  for (size_t i = 0; i < std::min(ta.size(), tb.size()); ++i) {
    EXPECT_EQ(ta[i].t_ns, tb[i].t_ns);
    worst_m = std::max(worst_m, (ta[i].p_w_x - tb[i].p_w_x).norm());
    worst_rad = std::max(worst_rad, ta[i].q_w_x.angularDistance(tb[i].q_w_x));
  }
  return {worst_m, worst_rad};
}

// The same trajectory: byte for byte (the file), hence also pose for pose.
void ExpectSameTrajectory(const fs::path& a, const fs::path& b) {
  const auto [worst_m, worst_rad] = WorstDifference(a, b);
  EXPECT_EQ(worst_m, 0.0);
  EXPECT_EQ(worst_rad, 0.0);
  EXPECT_EQ(ReadAll(a), ReadAll(b)) << a << " and " << b << " differ";
}

YAML::Node Metrics(const fs::path& run) { return YAML::LoadFile((run / "metrics.json").string()); }

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// Every single value in the run's metrics.json is a key a sweep can name (runner/metric_keys.h):
// the list is kept in step with what runs and replays write.
void ExpectEveryMetricKeyListed(const fs::path& run) {
  std::vector<std::string> unlisted;
  int leaves = 0;
  std::function<void(const YAML::Node&, const std::string&)> walk = [&](const YAML::Node& n, const std::string& key) {
    if (n.IsMap()) {
      for (const auto& kv : n) walk(kv.second, key.empty() ? kv.first.Scalar() : key + "." + kv.first.Scalar());
    } else if (n.IsScalar() || n.IsNull()) {  // NaN is written as null
      ++leaves;
      if (!runner::IsMetricKey(key)) unlisted.push_back(key);
    }  // lists (dynamic.objects) are no single value
  };
  walk(Metrics(run), "");
  EXPECT_GT(leaves, 20) << run;
  EXPECT_TRUE(unlisted.empty()) << run << ": metrics.json keys missing from runner/metric_keys.cc: "
                                << ::testing::PrintToString(unlisted);
}
double Ate(const fs::path& run) { return Metrics(run)["ate"]["rmse_m"].as<double>(); }

// Sum of tracking.csv's features_dropped column.
long FeaturesDropped(const fs::path& run) {
  const Csv csv = ReadCsv(run / "tracking.csv");
  const size_t col = csv.Column("features_dropped");
  long sum = 0;
  for (const auto& row : csv.rows) sum += std::stol(row.at(col));
  return sum;
}

// Same statuses and counts frame by frame (the timing columns aside).
void ExpectSameTracking(const fs::path& live, const fs::path& replay) {
  const std::vector<std::string> timing = {"track_ms", "dynamic_ms"};
  const std::vector<std::string> a = RowsWithout(ReadCsv(live / "tracking.csv"), timing);
  const std::vector<std::string> b = RowsWithout(ReadCsv(replay / "tracking.csv"), timing);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "tracking.csv row " << i + 1;
}

// A replay of the project's format scores its decisions against the recorded truth
// (mav0/objects0): dynamic.csv and every dynamic.* metric are the live run's, exactly.
void ExpectSameScoredDecisions(const fs::path& live, const fs::path& replay) {
  EXPECT_EQ(ReadText(replay / "dynamic.csv"), ReadText(live / "dynamic.csv"));
  const YAML::Node a = Metrics(live)["dynamic"], b = Metrics(replay)["dynamic"];
  ASSERT_TRUE(b["precision"].IsDefined() && b["recall"].IsDefined() && b["objects"].IsDefined());
  EXPECT_EQ(YAML::Dump(b), YAML::Dump(a));
  EXPECT_GT(b["scored_object_frames"].as<int>(), 0);
}

// The replay's object decisions are the live run's. Live, dynamic.csv has a row for every object
// the SLAM system reported (dynamic.object_frames of them) and one for every truly visible object
// that the detector missed (no features, not decided); a replay without truth (TUM with --masks)
// has only the former. Each replay row must be the live row of the same frame and object, less
// the truth columns, and there must be as many as the live run reported.
void ExpectSameDecisions(const fs::path& live, const fs::path& replay) {
  const std::vector<std::string> truth = {"visible_px", "truly_moving"};
  const Csv live_csv = ReadCsv(live / "dynamic.csv");
  const Csv replay_csv = ReadCsv(replay / "dynamic.csv");
  const std::vector<std::string> live_rows = RowsWithout(live_csv, truth);
  const std::vector<std::string> replay_rows = RowsWithout(replay_csv, truth);
  const size_t t_col = live_csv.Column("t_s"), object_col = live_csv.Column("object");
  const size_t features_col = live_csv.Column("features"), decided_col = live_csv.Column("decided_dynamic");
  std::map<std::pair<std::string, std::string>, size_t> live_row_of;  // (t, object) -> row
  for (size_t i = 0; i < live_csv.rows.size(); ++i) {
    live_row_of[{live_csv.rows[i].at(t_col), live_csv.rows[i].at(object_col)}] = i;
  }
  std::vector<bool> matched(live_rows.size(), false);
  for (size_t i = 0; i < replay_rows.size(); ++i) {
    const auto it = live_row_of.find({replay_csv.rows[i].at(t_col), replay_csv.rows[i].at(object_col)});
    ASSERT_NE(it, live_row_of.end()) << "replay dynamic.csv row " << i + 1 << " has no live row: " << replay_rows[i];
    EXPECT_EQ(live_rows[it->second], replay_rows[i]) << "dynamic.csv, replay row " << i + 1;
    matched[it->second] = true;
  }
  const int reported = Metrics(live)["dynamic"]["object_frames"].as<int>();
  EXPECT_GT(reported, 0);
  EXPECT_EQ(static_cast<int>(replay_rows.size()), reported);
  EXPECT_EQ(Metrics(replay)["dynamic"]["object_frames"].as<int>(), reported);
  EXPECT_EQ(Metrics(replay)["dynamic"]["decided_dynamic_share"].as<double>(),
            Metrics(live)["dynamic"]["decided_dynamic_share"].as<double>());
  for (size_t i = 0; i < live_rows.size(); ++i) {
    if (matched[i]) continue;  // a detector miss: nothing reported, nothing decided
    EXPECT_EQ(live_csv.rows[i].at(features_col), "0") << "live dynamic.csv row " << i + 1;
    EXPECT_EQ(live_csv.rows[i].at(decided_col), "0") << "live dynamic.csv row " << i + 1;
  }
}

// "12.345678901" (TUM seconds, 9 decimals at most) -> ns, exactly.
int64_t TumStampNs(const std::string& s) {
  const size_t dot = s.find('.');
  const std::string frac = dot == std::string::npos ? "" : s.substr(dot + 1);
  EXPECT_LE(frac.size(), 9u) << s;
  return std::stoll(s.substr(0, dot)) * 1000000000LL + (frac.empty() ? 0 : std::stoll(frac + std::string(9 - frac.size(), '0')));
}

// A masks folder (docs/MASKS.md) from a recording's seg0: every seg0 image copied under the name
// that `name_of` gives its stamp (ns), and seg0/instances.csv. Returns the number of masks.
template <typename NameOf>
int MasksFromSeg0(const fs::path& mav0, const fs::path& masks, NameOf name_of) {
  fs::create_directories(masks);
  fs::copy_file(mav0 / "seg0" / "instances.csv", masks / "instances.csv");
  const Csv list = ReadCsv(mav0 / "seg0" / "data.csv");
  int n = 0;
  for (const auto& row : list.rows) {
    fs::copy_file(mav0 / "seg0" / "data" / row.at(1), masks / name_of(std::stoll(row.at(0))));
    ++n;
  }
  return n;
}

// The live run of the stereo test and its dynamic stage at work.
void ExpectDynamicStageAtWork(const fs::path& live) {
  const YAML::Node m = Metrics(live);
  EXPECT_EQ(m["tracking"]["lost_frames"].as<int>(), 0);
  EXPECT_EQ(m["slam"]["dynamic_method"].as<std::string>(), "adaptive");
  const long dropped = FeaturesDropped(live);
  const double share = m["dynamic"]["decided_dynamic_share"].as<double>();
  std::printf("live %s: %ld features dropped, decided-dynamic share %.3f of %d object-frames\n", live.c_str(), dropped,
              share, m["dynamic"]["object_frames"].as<int>());
  EXPECT_GT(dropped, 0);
  EXPECT_GT(share, 0.0);
}

// A viqu-format replay of a live run: the same trajectory, tracking and decisions, every metrics
// key listed (runner/metric_keys.h), the same path length and share of path, no frame skipped.
void ExpectTheLiveRun(const fs::path& live, const fs::path& replay) {
  ExpectSameTrajectory(live / "trajectory_est.txt", replay / "trajectory_est.txt");
  ExpectSameTracking(live, replay);
  ExpectSameScoredDecisions(live, replay);
  ExpectEveryMetricKeyListed(live);
  ExpectEveryMetricKeyListed(replay);
  EXPECT_NEAR(Metrics(replay)["path_length_m"].as<double>(), Metrics(live)["path_length_m"].as<double>(), 1e-6);
  EXPECT_NEAR(Metrics(replay)["ate"]["rmse_pct_path"].as<double>(), Metrics(live)["ate"]["rmse_pct_path"].as<double>(), 1e-6);
  EXPECT_EQ(Metrics(replay)["camera"]["frames_skipped"].as<int>(), 0);
}

TEST(SlamReplay, ViquFormatReplaysTheLiveStereoRunWithItsDynamicDecisions) {
  Scenario s = ShortRoomWithPerson("", "full");
  // A worse detector: wrong categories (the same id under several) and spurious masks (new ids).
  s.sensors.segmentation.wrong_category_rate = 0.1;
  s.sensors.segmentation.false_positive_rate = 0.2;
  const fs::path live = Fresh("stereo_live");
  runner::RunOptions opt;
  opt.out_dir = live.string();
  opt.record = true;
  ASSERT_EQ(runner::RunScenario(s, opt), 0);
  ExpectDynamicStageAtWork(live);
  // Both detector faults reached the SLAM system: the person reported under another movable
  // category in some frame, and spurious masks reported.
  {
    const Csv d = ReadCsv(live / "dynamic.csv");
    const size_t object = d.Column("object"), category = d.Column("category");
    int miscategorised = 0, spurious = 0;
    for (const auto& row : d.rows) {
      if (row.at(object) == "walker" && row.at(category) != "person") ++miscategorised;
      if (row.at(object).rfind("spurious_", 0) == 0) ++spurious;
    }
    std::printf("live: %d frames with the person miscategorised, %d spurious-mask rows\n", miscategorised, spurious);
    EXPECT_GT(miscategorised, 0);
    EXPECT_GT(spurious, 0);
  }

  app::SlamArgs args;
  args.dataset_dir = live.string();
  args.format = "viqu";
  args.out_dir = Fresh("stereo_viqu").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  ExpectTheLiveRun(live, args.out_dir);
  // The replay fused leg odometry as the live run did: every frame but the first corrected it.
  EXPECT_TRUE(Metrics(args.out_dir)["lo"]["fused"].as<bool>());
  EXPECT_EQ(Metrics(args.out_dir)["lo"]["fusion_corrections"].as<int>(), Metrics(live)["lo"]["fusion_corrections"].as<int>());
  EXPECT_GT(Metrics(live)["lo"]["fusion_corrections"].as<int>(), 0);

  // EuRoC reader with seg0 as a masks folder (cam0 names are the stamps).
  const fs::path masks = Fresh("stereo_masks");
  EXPECT_GT(MasksFromSeg0(live / "dataset" / "mav0", masks, [](int64_t t) { return std::to_string(t) + ".png"; }), 150);
  args.dataset_dir = (live / "dataset").string();
  args.format = "euroc";
  args.masks_dir = masks.string();
  args.out_dir = Fresh("stereo_euroc").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const YAML::Node m = Metrics(args.out_dir);
  ExpectEveryMetricKeyListed(args.out_dir);
  EXPECT_EQ(m["tracking"]["lost_frames"].as<int>(), 0);
  std::printf("ATE live %.4f m, EuRoC replay %.4f m\n", Ate(live), Ate(args.out_dir));
  EXPECT_LT(Ate(args.out_dir), 2 * Ate(live) + 0.002);
  // EuRoC has an IMU and no encoders: in mode full imu0's gyro gives the motion prior of every
  // frame after the first two (the recording's first IMU sample, with the first frame, reads no
  // specific force: the attitude filter starts levelled at the next one, so the first frame has
  // no orientation to turn from). The same replay on vision alone guesses by constant velocity;
  // the gyro's guess must miss each frame's rotation by far less (the trot pitches and rolls).
  EXPECT_TRUE(m["imu"]["gyro_prior"].as<bool>());
  EXPECT_FALSE(m["lo"]["fused"].as<bool>());
  EXPECT_EQ(m["imu"]["gyro_priors_given"].as<int>(), m["tracking"]["frames"].as<int>() - 2);
  EXPECT_EQ(m["tracking"]["prior_frames_external"].as<int>(), m["tracking"]["frames"].as<int>() - 2);
  const double euroc_ate = Ate(args.out_dir);
  const std::string euroc_out = args.out_dir;
  args.sets = {"mode=visual_dynamic"};
  args.out_dir = Fresh("stereo_euroc_visual").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const YAML::Node v = Metrics(args.out_dir);
  EXPECT_FALSE(v["imu"]["gyro_prior"].as<bool>());
  EXPECT_EQ(v["tracking"]["prior_frames_external"].as<int>(), 0);
  const double gyro_deg = m["tracking"]["prior_err_deg_median"].as<double>();
  const double cv_deg = v["tracking"]["prior_err_deg_median"].as<double>();
  std::printf("EuRoC replay, prediction's miss per frame (median): gyro %.3f deg %.2f mm, constant velocity %.3f deg "
              "%.2f mm; ATE %.4f m with the gyro, %.4f m without\n",
              gyro_deg, m["tracking"]["prior_err_mm_median"].as<double>(), cv_deg,
              v["tracking"]["prior_err_mm_median"].as<double>(), euroc_ate, Ate(args.out_dir));
  // Measured: 0.086 deg against 1.75 deg (the leg odometry's prior of the live run: 0.082 deg).
  EXPECT_LT(gyro_deg, 0.18);
  EXPECT_LT(gyro_deg, cv_deg / 10);
  args.sets.clear();

  // Real-time mode (mapping on its own thread) on the same recording: not bit-reproducible, but
  // as good.
  const fs::path cfg = Fresh("realtime_config.yaml");
  std::ofstream(cfg) << "mapping: {mode: realtime}\n";
  args.dataset_dir = live.string();
  args.format = "viqu";
  args.masks_dir.clear();
  args.config = cfg.string();
  args.out_dir = Fresh("stereo_realtime").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const YAML::Node rt = Metrics(args.out_dir);
  EXPECT_EQ(rt["slam"]["mapping_mode"].as<std::string>(), "realtime");
  EXPECT_EQ(rt["tracking"]["lost_frames"].as<int>(), 0);
  EXPECT_GT(rt["timing"]["local_ba_count"].as<int>(), 0);
  std::printf("ATE live %.4f m, real-time mapping replay %.4f m\n", Ate(live), Ate(args.out_dir));
  EXPECT_LT(Ate(args.out_dir), 2 * Ate(live) + 0.002);
}

TEST(SlamReplay, RgbdRunReplaysFromSeg0AndFromTumWithMasks) {
  const fs::path cfg_dir = Fresh("rgbd_config");
  fs::create_directories(cfg_dir);
  const fs::path cfg = cfg_dir / "rgbd.yaml";
  // visual_dynamic: the TUM replay below has no encoders to fuse.
  std::ofstream(cfg) << "input: rgbd\nmode: visual_dynamic\n";
  Scenario s = ShortRoomWithPerson(cfg.string());
  s.sensors.segmentation.false_positive_rate = 0.2;
  const fs::path live = Fresh("rgbd_live");
  runner::RunOptions opt;
  opt.out_dir = live.string();
  opt.record = true;
  opt.record_tum = true;
  ASSERT_EQ(runner::RunScenario(s, opt), 0);
  EXPECT_EQ(Metrics(live)["slam"]["input"].as<std::string>(), "rgbd");
  ExpectDynamicStageAtWork(live);

  app::SlamArgs args;
  args.config = cfg.string();
  // The project's format in rgbd mode: depth0 holds the live depth's steps, seg0 the masks.
  args.dataset_dir = live.string();
  args.format = "viqu";
  args.out_dir = Fresh("rgbd_viqu").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  ExpectTheLiveRun(live, args.out_dir);

  // seg0 renamed to the rgb images' names (rgb.txt: "t rgb/<t>.png", in the order of seg0's rows).
  std::map<int64_t, std::string> rgb_name;
  {
    std::ifstream in(live / "dataset_tum" / "rgb.txt");
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      const std::vector<std::string> f = Split(line, ' ');
      ASSERT_EQ(f.size(), 2u) << line;
      rgb_name[TumStampNs(f[0])] = fs::path(f[1]).filename().string();
    }
  }
  const fs::path masks = Fresh("rgbd_masks");
  const int n = MasksFromSeg0(live / "dataset" / "mav0", masks, [&](int64_t t) {
    EXPECT_EQ(rgb_name.count(t), 1u) << t;
    return rgb_name[t];
  });
  EXPECT_EQ(static_cast<size_t>(n), rgb_name.size());

  args.dataset_dir = (live / "dataset_tum").string();
  args.format = "tum";
  args.masks_dir = masks.string();
  args.out_dir = Fresh("rgbd_tum_masks").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const fs::path with_masks = args.out_dir;
  ExpectSameTrajectory(live / "trajectory_est.txt", with_masks / "trajectory_est.txt");
  ExpectSameTracking(live, with_masks);
  ExpectSameDecisions(live, with_masks);

  // Without masks the dynamic stage has nothing to judge: another trajectory.
  args.masks_dir.clear();
  args.out_dir = Fresh("rgbd_tum_plain").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  const fs::path plain = args.out_dir;
  EXPECT_EQ(FeaturesDropped(plain), 0);
  const auto [diff_m, diff_rad] = WorstDifference(with_masks / "trajectory_est.txt", plain / "trajectory_est.txt");
  std::printf("TUM replay with masks against without: up to %.6f m, %.6f rad apart; ATE %.4f / %.4f m\n", diff_m,
              diff_rad, Ate(with_masks), Ate(plain));
  EXPECT_GT(diff_m, 1e-6);

  // The masks with dynamic.method none: exactly the replay without masks.
  args.masks_dir = masks.string();
  args.sets = {"dynamic.method=none"};
  args.out_dir = Fresh("rgbd_tum_masks_none").string();
  ASSERT_EQ(app::RunSlamCommand(args), 0);
  EXPECT_EQ(FeaturesDropped(args.out_dir), 0);
  ExpectSameTrajectory(plain / "trajectory_est.txt", fs::path(args.out_dir) / "trajectory_est.txt");
  ExpectSameTracking(plain, args.out_dir);
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

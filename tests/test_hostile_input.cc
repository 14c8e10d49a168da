// What a new user and a hostile input broke (issue 59), through the program: every case is a
// clean exit 2 naming the file (and line:column, or the key) or the behaviour the README states,
// never a figure the program cannot stand behind. Each test failed on the code before the fix.
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "common/output_lock.h"
#include "slam/io/instance_mask_folder.h"
#include "tests/scenario_text.h"
#include "tests/viqu_program.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;
using testing::ProgramResult;
using testing::ReadText;
using testing::RunViqu;
using testing::ScenarioWith;
using testing::WriteText;

const std::string kSource = VIQU_SOURCE_DIR;
const std::string kStatic = kSource + "/scenarios/static_room.yaml";
const std::string kPeople = kSource + "/scenarios/walking_people.yaml";
const std::string kSmall = " --set sensors.camera.width=320 --set sensors.camera.height=240";


// Expects exit 2 with viqu's message first, starting with `where` and holding `what`.
void ExpectBadInput(const ProgramResult& r, const std::string& where, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("viqu: " + where, 0), 0u) << "first line is not viqu's naming " << where << ":\n" << r.output;
  EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
}

// Exit 2 with a line of viqu's that starts with `where` and holds `what` (warnings and notes may
// come before it).
void ExpectRefused(const ProgramResult& r, const std::string& where, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const size_t at = r.output.find("viqu: " + where);
  ASSERT_NE(at, std::string::npos) << "no line of viqu's naming " << where << ":\n" << r.output;
  EXPECT_NE(r.output.substr(at, r.output.find('\n', at) - at).find(what), std::string::npos) << r.output;
}


class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
    dir_ = fs::temp_directory_path() /
           ("viqu_hostile_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    out_ = (dir_ / "out").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A short static_room run recorded in EuRoC and TUM layouts (outside the run folder, so that
  // tests may change it): DIR/ds (mav0), DIR/tum.
  void Record(const std::string& scenario = kStatic, const std::string& extra = "") {
    const fs::path run = dir_ / "rec";
    const ProgramResult r = RunViqu("run " + scenario + " --out " + run.string() + kSmall +
                                    " --set duration_s=0.6 --record --record-tum" + extra);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    fs::rename(run / "dataset", dir_ / "ds");
    fs::rename(run / "dataset_tum", dir_ / "tum");
  }
  fs::path dir_;
  std::string out_;
};

// Item 9 and the friction list: options, help, version.
TEST_F(HostileInput, TheCommandLineSaysWhatItTakes) {
  ExpectBadInput(RunViqu("run " + kStatic + " --out " + out_ + " --out " + out_ + "2"), "run: option --out given twice",
                 "viqu run --help");
  ExpectBadInput(RunViqu("report " + out_ + " --x a --x b"), "report: option --x given twice", "");
  const ProgramResult version = RunViqu("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.output.rfind("viqu 0.", 0), 0u) << version.output;
  EXPECT_NE(version.output.find("(git "), std::string::npos) << version.output;
  const ProgramResult help = RunViqu("--help");
  EXPECT_NE(help.output.find("130 / 143 stopped by SIGINT / SIGTERM"), std::string::npos) << help.output;
  const ProgramResult eval_help = RunViqu("eval --help");
  for (const char* part : {"t tx ty tz qx qy qz qw", "--sim3", "0.02 s", "exit 2"}) {
    EXPECT_NE(eval_help.output.find(part), std::string::npos) << part << "\n" << eval_help.output;
  }
  EXPECT_EQ(RunViqu("slam " + out_ + " --skip-bad-frames=0").exit_code, 2);
  // A SLAM setting in viqu slam's form given to viqu run: the scenario's form is suggested.
  ExpectBadInput(RunViqu("run " + kStatic + " --out " + out_ + " --set dynamic.method=none"),
                 "--set dynamic.method=none", "viqu run takes it as --set slam.dynamic.method=none");
}

// Item 9: a second YAML document and tags are refused where they stand.
TEST_F(HostileInput, YamlIsReadAsOneDocumentWithoutTags) {
  const std::string two = ScenarioWith(dir_, "scenario.yaml", "---\nname: ignored_before\n");
  const int lines = static_cast<int>(std::count(std::istreambuf_iterator<char>(*new std::ifstream(two)), {}, '\n'));
  ExpectBadInput(RunViqu("run " + two + " --out " + out_), two + ":" + std::to_string(lines - 1) + ":1:",
                 "a second YAML document");
  const std::string tagged = ScenarioWith(dir_, "scenario.yaml", "extra: !evil 2\n");
  ExpectBadInput(RunViqu("run " + tagged + " --out " + out_), tagged + ":", "YAML tag '!evil'");
  ExpectBadInput(RunViqu("run " + kStatic + " --out " + out_ + " --set 'duration_s=!!str 2'"), "--set duration_s=!!str 2",
                 "YAML tag");
  // A sweep that names no metric would tabulate nothing.
  WriteText(dir_ / "sweep.yaml", "scenarios: [" + kStatic + "]\nmetrics: []\n");
  ExpectBadInput(RunViqu("sweep " + (dir_ / "sweep.yaml").string() + " --out " + out_ + " --emit list"),
                 (dir_ / "sweep.yaml").string() + ":2:10:", "lists no metric");
  EXPECT_FALSE(fs::exists(out_));
}

// Item 3: readers refuse devices and pipes, and bound what they read.
TEST_F(HostileInput, ReadersRefuseWhatIsNoRegularFile) {
  std::string good;
  for (int i = 0; i < 5; ++i) good += std::to_string(i) + " " + std::to_string(0.1 * i) + " 0 0 0 0 0 1\n";
  WriteText(dir_ / "good.txt", good);
  ExpectBadInput(RunViqu("eval /dev/zero " + (dir_ / "good.txt").string()), "/dev/zero: not a regular file", "");
  ExpectBadInput(RunViqu("eval " + (dir_ / "good.txt").string() + " /dev/stdin < /dev/zero"), "/dev/stdin", "not a regular file");
  // A regular file of zeros: refused at the first line's bound, not read whole.
  std::ofstream(dir_ / "zeros.txt", std::ios::binary) << std::string(200000, '\0');
  ExpectBadInput(RunViqu("eval " + (dir_ / "zeros.txt").string() + " " + (dir_ / "good.txt").string()),
                 (dir_ / "zeros.txt").string() + ":1: line longer than", "");
  Record();
  fs::remove(dir_ / "tum" / "groundtruth.txt");
  fs::create_symlink("/dev/zero", dir_ / "tum" / "groundtruth.txt");
  ExpectBadInput(RunViqu("slam " + (dir_ / "tum").string() + " --format tum --out " + out_),
                 (dir_ / "tum" / "groundtruth.txt").string() + ": not a regular file", "");
  EXPECT_FALSE(fs::exists(out_));
}

// Item 4: a calibration no camera can have is refused naming its key.
TEST_F(HostileInput, AbsurdCalibrationIsRefusedNamingTheKey) {
  Record();
  WriteText(dir_ / "orb.yaml", "%YAML:1.0\nCamera.fx: 277.1\nCamera.fy: 277.1\nCamera.cx: 99999\nCamera.cy: 120\n");
  ExpectBadInput(RunViqu("slam " + (dir_ / "tum").string() + " --format tum --camera " + (dir_ / "orb.yaml").string() +
                         " --out " + out_),
                 (dir_ / "orb.yaml").string() + ":4:12: key 'Camera.cx'", "outside the 320x240 image");
  WriteText(dir_ / "fx.yaml", "%YAML:1.0\nCamera.fx: 1e300\nCamera.fy: 277.1\nCamera.cx: 160\nCamera.cy: 120\n");
  ExpectBadInput(RunViqu("slam " + (dir_ / "tum").string() + " --format tum --camera " + (dir_ / "fx.yaml").string() +
                         " --out " + out_),
                 (dir_ / "fx.yaml").string() + ":2:12: key 'Camera.fx'", "no focal length");
  // A EuRoC sensor.yaml whose distortion folds the image.
  const fs::path sensor = dir_ / "ds" / "mav0" / "cam0" / "sensor.yaml";
  std::string text = ReadText(sensor);
  const size_t key = text.find("distortion_coefficients:");
  ASSERT_NE(key, std::string::npos) << text;
  text.replace(key, text.find('\n', key) - key, "distortion_coefficients: [-3.0, 0.0, 0.0, 0.0]");
  WriteText(sensor, text);
  const ProgramResult r = RunViqu("slam " + (dir_ / "ds").string() + " --format euroc --out " + out_);
  ExpectBadInput(r, sensor.string() + ":", "key 'distortion_coefficients'");
  EXPECT_NE(r.output.find("folds the image"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out_));
}

// Items 7 and 8: unreadable frames are skipped up to the cap; broken masks are no "no detections".
TEST_F(HostileInput, BadFramesAreCappedAndBrokenMasksRefused) {
  Record();
  const fs::path data = dir_ / "ds" / "mav0" / "cam0" / "data";
  // Frames 2 and 5 (stamps 100 and 250 ms at 20 Hz) unreadable, each a lone one.
  WriteText(data / "100000000.png", "not a png");
  WriteText(data / "250000000.png", "not a png");
  const std::string replay = "slam " + (dir_ / "ds").string() + " --format euroc --set mode=visual --out " + out_;
  const ProgramResult capped = RunViqu(replay + " --skip-bad-frames");
  ExpectRefused(capped, (data / "250000000.png").string(), "as many as --skip-bad-frames 1 allows");
  const ProgramResult two = RunViqu(replay + " --skip-bad-frames 2");
  EXPECT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("frames, 2 unreadable skipped in"), std::string::npos) << two.output;

  // Masks for the TUM replay: instances.csv, and for one image a loop of links, then a mask far
  // larger than any 320x240 16-bit PNG.
  const fs::path masks = dir_ / "masks";
  fs::create_directories(masks);
  WriteText(masks / "instances.csv", "id,category,name\n1,box,crate\n");
  std::string first_rgb;
  for (const auto& e : fs::directory_iterator(dir_ / "tum" / "rgb")) {
    if (first_rgb.empty() || e.path().filename().string() < first_rgb) first_rgb = e.path().filename().string();
  }
  fs::create_symlink(masks / "loop_b", masks / first_rgb);
  fs::create_symlink(masks / first_rgb, masks / "loop_b");
  const std::string tum = "slam " + (dir_ / "tum").string() + " --format tum --masks " + masks.string() + " --out " + out_;
  ExpectRefused(RunViqu(tum), (masks / first_rgb).string(), "loop of links");
  fs::remove(masks / first_rgb);
  fs::remove(masks / "loop_b");
  std::ofstream(masks / first_rgb, std::ios::binary) << std::string(io::MaxMaskFileBytes(cv::Size(320, 240)) + 1, 'x');
  ExpectRefused(RunViqu(tum), (masks / first_rgb).string(), "too large for a mask image");
  // A recording's own segmentation image far larger than any 16-bit PNG of its size.
  const fs::path seg = dir_ / "ds" / "mav0" / "seg0" / "data" / "0.png";
  ASSERT_TRUE(fs::exists(seg));
  std::ofstream(seg, std::ios::app | std::ios::binary) << std::string(io::MaxMaskFileBytes(cv::Size(320, 240)), '\0');
  ExpectRefused(RunViqu("slam " + (dir_ / "ds").string() + " --format viqu --skip-bad-frames 2 --out " + out_), seg.string(),
                "too large for a 320x240 16-bit segmentation image");
  // The refused replays left the output folder as the last good one made it.
  EXPECT_EQ(YAML::LoadFile(out_ + "/metrics.json")["camera"]["frames_skipped"].as<int>(), 2);
}

// Item 10: a camera too small for the pyramid is blamed where the user made it small.
TEST_F(HostileInput, ATinyCameraIsNamedWhereItWasSet) {
  ExpectBadInput(RunViqu("run " + kStatic + " --out " + out_ + " --set sensors.camera.width=16 --set sensors.camera.height=16"),
                 "--set sensors.camera.height=16", "too small for the SLAM settings' ORB pyramid");
  const std::string file = ScenarioWith(dir_, "scenario.yaml", "");
  std::string text = ReadText(file);
  const size_t at = text.find("width: 640, height: 480");
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, 23, "width: 20, height: 16");
  WriteText(file, text);
  const long line = std::count(text.begin(), text.begin() + static_cast<long>(at), '\n') + 1;
  const long column = static_cast<long>(at - text.rfind('\n', at)) + 19;  // the value 16, 19 after "width"
  ExpectBadInput(RunViqu("run " + file + " --out " + out_),
                 file + ":" + std::to_string(line) + ":" + std::to_string(column) + " (sensors.camera.height)", "orb.num_levels");
}

// Item 2: no ATE from a trajectory that no measurement made; in `full` the leg odometry's is one.
TEST_F(HostileInput, ADarkRunHasNoAteInVisualButKeepsItInFull) {
  const std::string dark = "run " + kStatic + " --out " + out_ + kSmall + " --set duration_s=0.6 --set 'sensors.camera.dropouts=[[0, 10]]'";
  const ProgramResult visual = RunViqu(dark + " --set slam.mode=visual");
  EXPECT_EQ(visual.exit_code, 0) << visual.output;
  EXPECT_NE(visual.output.find("SLAM: no ATE (0 of 13 frames have a pose measured"), std::string::npos) << visual.output;
  YAML::Node m = YAML::LoadFile(out_ + "/metrics.json");
  EXPECT_TRUE(m["ate"]["unavailable"].IsDefined());
  EXPECT_FALSE(m["ate"]["rmse_m"].IsDefined());
  const ProgramResult full = RunViqu(dark + " --set slam.mode=full");
  EXPECT_EQ(full.exit_code, 0) << full.output;
  EXPECT_NE(full.output.find("SLAM: ATE "), std::string::npos) << full.output;
  m = YAML::LoadFile(out_ + "/metrics.json");
  EXPECT_TRUE(m["ate"]["rmse_m"].IsDefined());
  EXPECT_FALSE(m["ate"]["unavailable"].IsDefined());
}

// Item 9: a robot with nothing to do is warned about.
TEST_F(HostileInput, ARobotWithoutACommandIsWarnedAbout) {
  const ProgramResult r = RunViqu("run " + kStatic + " --out " + out_ + kSmall +
                                  " --no-slam --set duration_s=0.1 --set 'robot.command.waypoints=[]'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: " + kStatic + ": robot.command has no waypoints and no velocity schedule"),
            std::string::npos)
      << r.output;
}

// Item 5: one writer per output folder.
TEST_F(HostileInput, ASecondCommandIntoAFolderInUseIsRefused) {
  const pid_t first = testing::SpawnViqu({"run", kStatic, "--out", out_, "--set", "sensors.camera.width=320", "--set",
                                          "sensors.camera.height=240", "--set", "duration_s=60"},
                                         (dir_ / "first.log").string());
  // Until the first run holds the lock and has written its record.
  std::error_code ec;
  for (int i = 0; i < 3000; ++i) {
    if (fs::exists(OutputLockPath(out_)) && fs::file_size(OutputLockPath(out_), ec) > 0 && !ec) break;
    ::usleep(10000);
  }
  const ProgramResult second = RunViqu("run " + kStatic + " --out " + out_ + kSmall + " --set duration_s=0.1");
  ExpectBadInput(second, "output folder " + out_ + " is in use by", "(pid " + std::to_string(first) + ")");
  ::kill(first, SIGTERM);
  EXPECT_EQ(testing::WaitViqu(first), 143);
  // The first run's folder is its own, marked interrupted; the lock is gone with it.
  EXPECT_TRUE(fs::exists(fs::path(out_) / "run_incomplete.json"));
  EXPECT_FALSE(fs::exists(OutputLockPath(out_)));
  // viqu sweep takes the same lock (viqu slam: AReplayIsScoredAndReportedAsItsLiveRun).
  const OutputLock held(out_, "a test");
  WriteText(dir_ / "sweep.yaml", "scenarios: [" + kStatic + "]\n");
  ExpectBadInput(RunViqu("sweep " + (dir_ / "sweep.yaml").string() + " --out " + out_ + " --emit list"),
                 "output folder " + out_ + " is in use by a test", "");
}

// Item 1 and the friction list: a replay of a recording with objects scores its dynamic-object
// decisions as the live run did, viqu report draws it, and the scenario form of --set works.
TEST_F(HostileInput, AReplayIsScoredAndReportedAsItsLiveRun) {
  const fs::path live = dir_ / "live";
  const ProgramResult run = RunViqu("run " + kPeople + " --out " + live.string() + kSmall + " --set duration_s=1.5 --record");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(fs::exists(live / "dataset" / "mav0" / "objects0" / "data.csv"));
  const ProgramResult replay = RunViqu("slam " + live.string() + " --out " + out_);
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_EQ(ReadText(fs::path(out_) / "dynamic.csv"), ReadText(live / "dynamic.csv"));
  const YAML::Node a = YAML::LoadFile((live / "metrics.json").string())["dynamic"];
  const YAML::Node b = YAML::LoadFile(out_ + "/metrics.json")["dynamic"];
  ASSERT_TRUE(b["precision"].IsDefined() && b["recall"].IsDefined());
  EXPECT_EQ(a["precision"].as<std::string>(), b["precision"].as<std::string>());
  EXPECT_EQ(a["recall"].as<std::string>(), b["recall"].as<std::string>());
  EXPECT_EQ(a["scored_object_frames"].as<int>(), b["scored_object_frames"].as<int>());
  EXPECT_GT(b["scored_object_frames"].as<int>(), 0);
  const ProgramResult report = RunViqu("report " + out_);
  EXPECT_EQ(report.exit_code, 0) << report.output;
  // Method none judges nothing: precision and recall are null, not 0; the scenario's form of the
  // key is the same setting as viqu slam's.
  const std::string none_a = (dir_ / "none_a").string(), none_b = (dir_ / "none_b").string();
  ASSERT_EQ(RunViqu("slam " + live.string() + " --out " + none_a + " --set slam.dynamic.method=none").exit_code, 0);
  ASSERT_EQ(RunViqu("slam " + live.string() + " --out " + none_b + " --set dynamic.method=none").exit_code, 0);
  EXPECT_EQ(ReadText(fs::path(none_a) / "slam_settings.yaml"), ReadText(fs::path(none_b) / "slam_settings.yaml"));
  EXPECT_EQ(ReadText(fs::path(none_a) / "trajectory_est.txt"), ReadText(fs::path(none_b) / "trajectory_est.txt"));
  const YAML::Node none = YAML::LoadFile(none_a + "/metrics.json")["dynamic"];
  EXPECT_TRUE(none["recall"].IsNull()) << none["recall"];
  EXPECT_TRUE(none["precision"].IsNull()) << none["precision"];
  EXPECT_GT(none["scored_object_frames"].as<int>(), 0);
  ExpectBadInput(RunViqu("slam " + live.string() + " --out " + none_a + " --set slam.dynamic.method=nothing"),
                 "--set slam.dynamic.method=nothing", "");
  // viqu slam takes the output folder's lock as viqu run does (ASecondCommandIntoAFolderInUseIsRefused).
  const OutputLock held(out_, "a test");
  ExpectBadInput(RunViqu("slam " + live.string() + " --out " + out_), "output folder " + out_ + " is in use by a test", "");
}

}  // namespace
}  // namespace viqu

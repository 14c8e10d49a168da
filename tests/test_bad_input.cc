// Bad input through the program (issue 11): every case is exit 2 with viqu's message first,
// naming the file (and line:column for YAML), before any output is written; none exits 0 with
// wrong figures.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/scenario_text.h"
#include "tests/viqu_program.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;
using testing::ProgramResult;
using testing::RunViqu;
using testing::ScenarioWith;
using testing::WriteText;

const std::string kSource = VIQU_SOURCE_DIR;
const std::string kScenario = kSource + "/scenarios/static_room.yaml";
const std::string kSmall = " --set sensors.camera.width=320 --set sensors.camera.height=240";

fs::path Fresh(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_bad_input_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}


int LineCount(const std::string& path) {
  std::ifstream in(path);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}


// Expects exit 2 with viqu's message on the first line, starting with `where` and holding `what`.
void ExpectBadInput(const ProgramResult& r, const std::string& where, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("viqu: " + where, 0), 0u) << "first line is not viqu's naming " << where << ":\n" << r.output;
  EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
    dir_ = Fresh(::testing::UnitTest::GetInstance()->current_test_info()->name());
    out_ = (dir_ / "out").string();
  }
  // Nothing was written: no output folder, no partial folder.
  void ExpectNoOutput() const {
    for (const auto& e : fs::directory_iterator(dir_)) {
      EXPECT_EQ(e.path().filename().string().find("out"), std::string::npos) << e.path() << " was written";
    }
  }
  fs::path dir_;
  std::string out_;
};

TEST_F(BadInput, ScenarioChecksRunBeforeTheSimulation) {
  ExpectBadInput(RunViqu("run /dev/zero --out " + out_), "/dev/zero", "not a regular file");
  ExpectBadInput(RunViqu("run " + dir_.string() + " --out " + out_), dir_.string(), "is a directory");

  const std::string fovy = ScenarioWith(dir_, "fovy.yaml", "");
  ExpectBadInput(RunViqu("run " + fovy + " --out " + out_ + " --set sensors.camera.fovy_deg=179"),
                 "--set sensors.camera.fovy_deg=179", "(0, 170]");

  const std::string tall = ScenarioWith(dir_, "tall.yaml",
                                        "obstacles:\n  - {name: giant, category: person, size_m: [3.1], path: [[1, 1]]}\n");
  ExpectBadInput(RunViqu("run " + tall + " --out " + out_), tall + ":", "a person's height must be within [0.5, 2.5] m, got 3.1");
  // The line (the file's last) and column of the size.
  EXPECT_NE(RunViqu("run " + tall + " --out " + out_).output.find(tall + ":" + std::to_string(LineCount(tall)) + ":"),
            std::string::npos);

  std::string many = "obstacles:\n";
  for (int i = 0; i < 1001; ++i) many += "  - {name: b" + std::to_string(i) + ", path: [[3, 3]]}\n";
  const std::string crowd = ScenarioWith(dir_, "crowd.yaml", many);
  ExpectBadInput(RunViqu("run " + crowd + " --out " + out_), crowd + ":", "at most 1000 obstacles, got 1001");

  // A world without a floor: the world file is named.
  std::ifstream room_in(kSource + "/models/worlds/room.xml");
  std::string room((std::istreambuf_iterator<char>(room_in)), {});
  room.replace(room.find("name=\"floor\""), 12, "name=\"rug\"");
  for (size_t at; (at = room.find("../../assets")) != std::string::npos;) room.replace(at, 12, kSource + "/assets");
  WriteText(dir_ / "no_floor.xml", room);
  ExpectBadInput(RunViqu("run " + kScenario + " --out " + out_ + " --set world=" + (dir_ / "no_floor.xml").string()),
                 (dir_ / "no_floor.xml").string(), "no geom named 'floor'");
  // An attribute MuJoCo refuses: the world file's own line, not the composed scene's.
  std::string bogus = room;
  const size_t rug = bogus.find("name=\"rug\"");
  bogus.insert(rug, "bogus_attr=\"1\" ");
  const int bogus_line = 1 + static_cast<int>(std::count(bogus.begin(), bogus.begin() + static_cast<std::ptrdiff_t>(rug), '\n'));
  WriteText(dir_ / "bogus.xml", bogus);
  ExpectBadInput(RunViqu("run " + kScenario + " --out " + out_ + " --set world=" + (dir_ / "bogus.xml").string()),
                 (dir_ / "bogus.xml").string() + ":" + std::to_string(bogus_line) + ": ", "unrecognized attribute: 'bogus_attr'");

  // SLAM settings whose pyramid leaves nothing of the image: the settings line is named.
  std::ifstream settings_in(kSource + "/slam/config/default.yaml");
  std::string settings((std::istreambuf_iterator<char>(settings_in)), {});
  for (size_t at; (at = settings.find("scale_factor: 1.2 ")) != std::string::npos;) settings.replace(at, 17, "scale_factor: 3");
  WriteText(dir_ / "slam.yaml", settings);
  const ProgramResult pyramid =
      RunViqu("run " + kScenario + " --out " + out_ + kSmall + " --set slam.config=" + (dir_ / "slam.yaml").string());
  ExpectBadInput(pyramid, (dir_ / "slam.yaml").string() + ":13:", "orb.num_levels 8 at orb.scale_factor 3 shrinks the 320x240 image to 0x0 px");
  ExpectNoOutput();
}

// A scenario's slam.* key whose value the SLAM settings refuse (the scenario loader checks only
// its kind): the message names the scenario's line and column, or the --set that wrote it.
TEST_F(BadInput, ASlamSettingFromAScenarioIsNamedWhereItWasWritten) {
  const std::string stereo = ScenarioWith(dir_, "stereo.yaml", "  stereo: {near_right_weight_ba: 3}\n");
  ExpectBadInput(RunViqu("run " + stereo + " --out " + out_), stereo + ":" + std::to_string(LineCount(stereo)) + ":",
                 "'stereo.near_right_weight_ba' expected a number in [0, 1], got '3'");
  const std::string lo = ScenarioWith(dir_, "lo.yaml", "  lo:\n    accel_noise: 0.3\n    attitude_gain: 500\n");
  ExpectBadInput(RunViqu("run " + lo + " --out " + out_), lo + ":" + std::to_string(LineCount(lo)) + ":",
                 "'lo.attitude_gain' expected a number in [0, 100], got '500'");
  const std::string adaptive =
      ScenarioWith(dir_, "adaptive.yaml", "  dynamic:\n    th_d: 0.1\n    adaptive: {static_pose_min_share: 2}\n");
  ExpectBadInput(RunViqu("run " + adaptive + " --out " + out_),
                 adaptive + ":" + std::to_string(LineCount(adaptive)) + ":", "static_pose_min_share");
  ExpectBadInput(RunViqu("run " + kScenario + " --out " + out_ + " --set slam.stereo.near_right_weight_ba=3"),
                 "--set slam.stereo.near_right_weight_ba=3", "expected a number in [0, 1], got '3'");
  ExpectNoOutput();
}

TEST_F(BadInput, OutputFolderThatCannotBeARunFolder) {
  WriteText(dir_ / "file", "x");
  ExpectBadInput(RunViqu("run " + kScenario + " --out " + (dir_ / "file").string()), "output folder " + (dir_ / "file").string(),
                 "is not a folder");
  fs::create_directories(dir_ / "mine");
  WriteText(dir_ / "mine" / "notes.txt", "mine");
  ExpectBadInput(RunViqu("run " + kScenario + " --out " + (dir_ / "mine").string()), "output folder " + (dir_ / "mine").string(),
                 "--force");
  EXPECT_TRUE(fs::exists(dir_ / "mine" / "notes.txt"));
  ExpectBadInput(RunViqu("run " + kScenario + " --out /"), "output folder '/'", "a root");
  ExpectBadInput(RunViqu("run " + kScenario + " --out .."), "output folder ..", "holds it");
}

TEST_F(BadInput, EvalNeverPrintsWrongFigures) {
  auto traj = [&](const std::string& name, const std::string& text) {
    WriteText(dir_ / name, text);
    return (dir_ / name).string();
  };
  std::string good_text;
  for (int i = 0; i < 10; ++i) good_text += std::to_string(i) + " " + std::to_string(0.1 * i) + " 0 0 0 0 0 1\n";
  const std::string good = traj("good.txt", good_text);
  ASSERT_EQ(RunViqu("eval " + good + " " + good).exit_code, 0);

  const std::string huge = traj("huge.txt", "0 1e200 0 0 0 0 0 1\n1 2e200 0 0 0 0 0 1\n2 3e200 1 0 0 0 0 1\n");
  ExpectBadInput(RunViqu("eval " + huge + " " + good), huge + ":1:", "position outside");
  const std::string late = traj("late.txt", "1e300 0 0 0 0 0 0 1\n");
  ExpectBadInput(RunViqu("eval " + late + " " + good), late + ":1:", "timestamp outside");
  const std::string early = traj("early.txt", "-9223372036.854775808 0 0 0 0 0 0 1\n");
  ExpectBadInput(RunViqu("eval " + early + " " + good), early + ":1:", "timestamp outside");
  const std::string dup = traj("dup.txt", "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\n3 0 0 0 0 0 0 1\n");
  ExpectBadInput(RunViqu("eval " + dup + " " + good), dup + ":2:", "repeats");
  const std::string empty = traj("empty.txt", "");
  ExpectBadInput(RunViqu("eval " + empty + " " + good), empty, "holds no poses");
  const std::string comments = traj("comments.txt", "# t tx ty tz qx qy qz qw\n");
  ExpectBadInput(RunViqu("eval " + good + " " + comments), comments, "holds no poses");
  ExpectBadInput(RunViqu("eval " + dir_.string() + " " + good), dir_.string(), "is a directory");
  const std::string shifted = traj("shifted.txt", "100 0 0 0 0 0 0 1\n101 1 0 0 0 0 0 1\n102 2 0 0 0 0 0 1\n");
  ExpectBadInput(RunViqu("eval " + shifted + " " + good), shifted + " and " + good, "0 poses associated");
  ExpectBadInput(RunViqu("eval " + good + " " + good + " --delta 1000"), good, "no pose pair 1000 associated poses apart");
  ExpectBadInput(RunViqu("eval " + good + " " + good + " --delta-m 50"), good, "no pose pair");
  EXPECT_EQ(RunViqu("eval " + good + " " + good + " --delta 2147483648").exit_code, 2);
  EXPECT_EQ(RunViqu("eval " + good + " " + good + " --delta 2 --delta-m 0.5").exit_code, 2);
}

// A recorded dataset (mav0 layout) outside any run folder, that tests may damage.
fs::path RecordDataset(const fs::path& dir) {
  const fs::path run = dir / "rec";
  const ProgramResult r = RunViqu("run " + kScenario + " --out " + run.string() + kSmall + " --set duration_s=0.6 --record");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  fs::rename(run / "dataset", dir / "ds");
  return dir / "ds";
}

TEST_F(BadInput, DamagedRecordingsAreNamedByViquFirst) {
  const fs::path ds = RecordDataset(dir_);
  // A truncated first PNG: viqu's line comes first (libpng prints nothing).
  const fs::path png = ds / "mav0" / "cam0" / "data" / "0.png";
  fs::resize_file(png, 3000);
  const ProgramResult truncated = RunViqu("slam " + ds.string() + " --format euroc --set mode=visual --out " + out_);
  ExpectBadInput(truncated, png.string(), "corrupt PNG (truncated");
  EXPECT_EQ(truncated.output.find("libpng"), std::string::npos) << truncated.output;
  fs::copy_file(ds / "mav0" / "cam0" / "data" / "50000000.png", png, fs::copy_options::overwrite_existing);
  // A broken URDF (mode full reads it): urdfdom's reason comes after viqu's line, not before.
  WriteText(ds / "mav0" / "robot.urdf", "<robot name=\"r\"><link name=\"a\"></robot>");
  const ProgramResult urdf = RunViqu("slam " + ds.string() + " --format viqu --set mode=full --out " + out_);
  ExpectBadInput(urdf, (ds / "mav0" / "robot.urdf").string(), "cannot parse URDF");
  ExpectNoOutput();
}

TEST_F(BadInput, ReplayWhoseTruthCannotBeAlignedKeepsItsTrajectory) {
  const fs::path ds = RecordDataset(dir_);
  // Ground truth stamps 1000 s after the images: nothing associates.
  const fs::path gt = ds / "mav0" / "state_groundtruth_estimate0" / "data.csv";
  std::ifstream in(gt);
  std::string line, shifted;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#') line = std::to_string(std::stoll(line.substr(0, line.find(','))) + 1000'000'000'000LL) + line.substr(line.find(','));
    shifted += line + "\n";
  }
  in.close();
  WriteText(gt, shifted);
  const ProgramResult r = RunViqu("slam " + ds.string() + " --format euroc --set mode=visual --out " + out_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("no ATE"), std::string::npos) << r.output;
  std::ifstream metrics(fs::path(out_) / "metrics.json");
  const std::string m((std::istreambuf_iterator<char>(metrics)), {});
  EXPECT_NE(m.find("\"unavailable\": \"the estimate cannot be aligned"), std::string::npos) << m;
  EXPECT_EQ(m.find("\"rmse_m\""), std::string::npos) << m;
  EXPECT_TRUE(fs::file_size(fs::path(out_) / "trajectory_est.txt") > 0);
  EXPECT_TRUE(fs::exists(fs::path(out_) / "run_complete.json"));
}

}  // namespace
}  // namespace viqu

// Command-line parsing of every subcommand of DESIGN.md.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "apps/cli.h"
#include "apps/usage_error.h"
#include "tests/viqu_program.h"
#include "read_all.h"

namespace viqu::app {
namespace {

CliArgs Parse(std::vector<const char*> args) {
  args.insert(args.begin(), "viqu");
  return ParseCommandLine(static_cast<int>(args.size()), args.data());
}

std::string UsageErrorOf(std::vector<const char*> args) {
  try {
    Parse(std::move(args));
  } catch (const UsageError& e) {
    return e.what();
  }
  return "<no UsageError>";
}

TEST(Cli, RunWithAllOptions) {
  const CliArgs a = Parse({"run", "scenarios/static_room.yaml", "--out", "runs/x", "--set",
                           "sensors.camera.rate_hz=10", "--set=obstacles=[]", "--no-slam", "--record", "--video"});
  ASSERT_EQ(a.command, Command::kRun);
  EXPECT_EQ(a.run.scenario, "scenarios/static_room.yaml");
  EXPECT_EQ(a.run.options.out_dir, "runs/x");
  EXPECT_EQ(a.run.sets, (std::vector<std::string>{"sensors.camera.rate_hz=10", "obstacles=[]"}));
  EXPECT_FALSE(a.run.options.slam);
  EXPECT_TRUE(a.run.options.record);
  EXPECT_TRUE(a.run.options.video);
}

TEST(Cli, ForceCameraAndTheRecordedCommandLine) {
  const CliArgs a = Parse({"run", "s.yaml", "--out", "my runs/x", "--force"});
  EXPECT_TRUE(a.run.options.force);
  EXPECT_EQ(a.command_line, "viqu run s.yaml --out 'my runs/x' --force");
  const CliArgs b = Parse({"slam", "d", "--camera", "cam.yaml", "--force"});
  EXPECT_EQ(b.slam.camera, "cam.yaml");
  EXPECT_TRUE(b.slam.force);
  EXPECT_FALSE(Parse({"run", "s.yaml"}).run.options.force);
  EXPECT_EQ(Parse({"run", "it's.yaml"}).command_line, "viqu run 'it'\\''s.yaml'");
}

TEST(Cli, RunDefaults) {
  const CliArgs a = Parse({"run", "s.yaml"});
  EXPECT_TRUE(a.run.options.out_dir.empty());
  EXPECT_TRUE(a.run.options.slam);
  EXPECT_FALSE(a.run.options.record);
  EXPECT_FALSE(a.run.options.video);
  EXPECT_TRUE(a.run.sets.empty());
  // Options may come before the scenario; values may start with '-'.
  const CliArgs b = Parse({"run", "--out=o", "--set", "robot.start.yaw_deg=-30", "s.yaml"});
  EXPECT_EQ(b.run.scenario, "s.yaml");
  EXPECT_EQ(b.run.options.out_dir, "o");
  EXPECT_EQ(b.run.sets, (std::vector<std::string>{"robot.start.yaw_deg=-30"}));
}

TEST(Cli, OtherSubcommandsParseTheirOptions) {
  const CliArgs s = Parse({"slam", "runs/x", "--format", "euroc", "--config", "c.yaml", "--out", "o"});
  ASSERT_EQ(s.command, Command::kSlam);
  EXPECT_EQ(s.slam.dataset_dir, "runs/x");
  EXPECT_EQ(s.slam.format, "euroc");
  EXPECT_EQ(s.slam.config, "c.yaml");
  EXPECT_EQ(s.slam.out_dir, "o");
  EXPECT_EQ(Parse({"slam", "d"}).slam.format, "viqu");
  EXPECT_TRUE(Parse({"slam", "d"}).slam.masks_dir.empty());
  EXPECT_TRUE(Parse({"slam", "d"}).slam.sets.empty());
  const CliArgs m = Parse({"slam", "d", "--format=tum", "--masks", "yolo_masks", "--set", "tracking.min_inliers=40",
                           "--set=mapping.mode=realtime"});
  EXPECT_EQ(m.slam.format, "tum");
  EXPECT_EQ(m.slam.masks_dir, "yolo_masks");
  EXPECT_EQ(m.slam.sets, (std::vector<std::string>{"tracking.min_inliers=40", "mapping.mode=realtime"}));

  const CliArgs e = Parse({"eval", "est.txt", "gt.txt", "--json"});
  ASSERT_EQ(e.command, Command::kEval);
  EXPECT_EQ(e.eval.estimate, "est.txt");
  EXPECT_EQ(e.eval.ground_truth, "gt.txt");
  EXPECT_TRUE(e.eval.json);

  const CliArgs w = Parse({"sweep", "sweep.yaml", "--jobs", "4"});
  ASSERT_EQ(w.command, Command::kSweep);
  EXPECT_EQ(w.sweep.sweep_file, "sweep.yaml");
  EXPECT_EQ(w.sweep.jobs, 4);
  EXPECT_GE(Parse({"sweep", "s.yaml"}).sweep.jobs, 1);  // the number of cores
  const CliArgs all = Parse({"sweep", "s.yaml", "--out", "d", "--resume", "--emit", "slurm"});
  EXPECT_EQ(all.sweep.out_dir, "d");
  EXPECT_TRUE(all.sweep.resume);
  EXPECT_EQ(all.sweep.emit, "slurm");
  EXPECT_EQ(Parse({"sweep", "--collect", "d"}).sweep.collect_dir, "d");
  const CliArgs rep = Parse({"report", "sweeps/x", "--x", "a.b", "--metric=ate.rmse_m"});
  EXPECT_EQ(rep.command, Command::kReport);
  EXPECT_EQ(rep.report.dir, "sweeps/x");
  EXPECT_EQ(rep.report.tool_args, (std::vector<std::string>{"--x", "a.b", "--metric", "ate.rmse_m"}));
  EXPECT_TRUE(Parse({"run", "s.yaml", "--report"}).run.options.report);
  EXPECT_EQ(UsageErrorOf({"report"}), "report: missing DIR");
  EXPECT_EQ(UsageErrorOf({"sweep", "s.yaml", "--emit", "pbs"}), "sweep: --emit expects slurm or list, got 'pbs'");
  EXPECT_EQ(UsageErrorOf({"sweep", "s.yaml", "--collect", "d"}), "sweep: --collect DIR takes no sweep file and no other option");

  const CliArgs v = Parse({"view", "s.yaml", "--set", "seed=3"});
  ASSERT_EQ(v.command, Command::kView);
  EXPECT_EQ(v.view.scenario, "s.yaml");
  EXPECT_EQ(v.view.sets, (std::vector<std::string>{"seed=3"}));
  EXPECT_EQ(v.view.speed, 1.0);
  EXPECT_FALSE(v.view.paused);
  EXPECT_FALSE(v.view.exit_at_end);
  EXPECT_TRUE(v.view.options.slam);
  const CliArgs vw = Parse({"view", "s.yaml", "--speed", "0.25", "--paused", "--exit-at-end", "--screenshot", "a.png",
                           "--out", "o", "--force", "--no-slam"});
  EXPECT_EQ(vw.view.speed, 0.25);
  EXPECT_TRUE(vw.view.paused);
  EXPECT_TRUE(vw.view.exit_at_end);
  EXPECT_EQ(vw.view.screenshot, "a.png");
  EXPECT_EQ(vw.view.options.out_dir, "o");
  EXPECT_TRUE(vw.view.options.force);
  EXPECT_FALSE(vw.view.options.slam);
  EXPECT_EQ(Parse({"view", "s.yaml", "--speed=0"}).view.speed, 0.0);
  for (const char* bad : {"-1", "fast", "nan", "inf", ""}) {
    EXPECT_EQ(UsageErrorOf({"view", "s.yaml", "--speed", bad}),
              std::string("view: --speed expects a number >= 0 (simulated seconds per second; 0: as fast as it runs), got '") +
                  bad + "'");
  }
  EXPECT_EQ(UsageErrorOf({"view", "s.yaml", "--record"}), "view: unknown option --record");
}

TEST(Cli, Help) {
  EXPECT_EQ(Parse({"--help"}).command, Command::kHelp);
  EXPECT_EQ(Parse({"--help"}).help_topic, "");
  const CliArgs r = Parse({"run", "--help"});
  EXPECT_EQ(r.command, Command::kHelp);
  EXPECT_EQ(r.help_topic, "run");
  EXPECT_EQ(Parse({"help", "eval"}).help_topic, "eval");
  EXPECT_NE(UsageText().find("viqu run SCENARIO.yaml"), std::string::npos);
  EXPECT_NE(UsageText().find("viqu sweep SWEEP.yaml [--jobs N]"), std::string::npos);
  EXPECT_NE(UsageText("run").find("--no-slam"), std::string::npos);
  EXPECT_NE(UsageText("slam").find("--masks DIR"), std::string::npos);
  EXPECT_NE(UsageText("slam").find("--set K=V"), std::string::npos);
}

TEST(Cli, UsageErrors) {
  EXPECT_EQ(UsageErrorOf({}), "missing command");
  EXPECT_EQ(UsageErrorOf({"fly"}), "unknown command 'fly'");
  EXPECT_EQ(UsageErrorOf({"run"}), "run: missing SCENARIO.yaml");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "b.yaml"}), "run: unexpected argument 'b.yaml'");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--out"}), "run: option --out needs a value");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--fast"}), "run: unknown option --fast");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--record=yes"}), "run: option --record takes no value");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--set", "duty"}), "run: --set expects key.path=value, got 'duty'");
  EXPECT_EQ(UsageErrorOf({"slam", "d", "--format", "kitti"}),
            "slam: --format expects viqu, euroc or tum, got 'kitti'");
  EXPECT_EQ(UsageErrorOf({"slam", "d", "--set", "tracking.min_inliers"}),
            "slam: --set expects key.path=value, got 'tracking.min_inliers'");
  EXPECT_EQ(UsageErrorOf({"slam", "d", "--masks"}), "slam: option --masks needs a value");
  EXPECT_EQ(UsageErrorOf({"eval", "est.txt"}), "eval: missing GT.txt");
  // --delta is a frame count that fits; it does not wrap or truncate, and excludes --delta-m.
  EXPECT_EQ(UsageErrorOf({"eval", "e", "g", "--delta", "2147483648"}),
            "eval: --delta expects a whole number of frames from 1 to 1000000, got '2147483648'");
  EXPECT_EQ(UsageErrorOf({"eval", "e", "g", "--delta", "1.5"}),
            "eval: --delta expects a whole number of frames from 1 to 1000000, got '1.5'");
  EXPECT_EQ(UsageErrorOf({"eval", "e", "g", "--delta-m", "inf"}),
            "eval: --delta-m expects a positive number of metres, got 'inf'");
  EXPECT_EQ(UsageErrorOf({"eval", "e", "g", "--delta", "3", "--delta-m", "0.5"}),
            "eval: --delta and --delta-m exclude each other");
  EXPECT_EQ(Parse({"eval", "e", "g", "--delta", "1000000"}).eval.delta_frames, 1000000);
  EXPECT_EQ(UsageErrorOf({"run", "s.yaml", "--force=yes"}), "run: option --force takes no value");
  EXPECT_EQ(UsageErrorOf({"sweep", "s.yaml", "--jobs", "0"}),
            "sweep: --jobs expects a whole number from 1 to 1024, got '0'");
  EXPECT_EQ(UsageErrorOf({"help", "fly"}), "help: unknown command 'fly'");
}

// The program's exit codes and messages (DESIGN.md): 0 ok, 2 bad input or usage.
using viqu::testing::ProgramResult;
using viqu::testing::RunViqu;

TEST(CliProgram, ExitCodesAndMessages) {
  if (!std::filesystem::exists(std::string(VIQU_BINARY_DIR) + "/apps/viqu")) {
    GTEST_SKIP() << "the viqu program is not built";
  }
  EXPECT_EQ(RunViqu("--help").exit_code, 0);
  const ProgramResult none = RunViqu("");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.output.find("usage: viqu COMMAND"), std::string::npos) << none.output;
  // A command's usage error points at its help instead of printing every command's usage.
  const ProgramResult usage = RunViqu("eval a.txt b.txt --delta 0");
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(usage.output.rfind("viqu: eval: --delta", 0), 0u) << usage.output;
  EXPECT_NE(usage.output.find("(viqu eval --help lists its options)\n"), std::string::npos) << usage.output;
  EXPECT_EQ(usage.output.find("viqu run SCENARIO"), std::string::npos) << usage.output;
  const ProgramResult missing = RunViqu("run /nonexistent/scenario.yaml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.output, "viqu: /nonexistent/scenario.yaml: file not found\n");

  const std::string dir = ::testing::TempDir() + "viqu_cli_bad";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/bad.yaml") << "name: x\nworld: [oops\n";
  const ProgramResult malformed = RunViqu("run " + dir + "/bad.yaml");
  EXPECT_EQ(malformed.exit_code, 2);
  EXPECT_EQ(malformed.output.rfind("viqu: " + dir + "/bad.yaml:3:1: YAML syntax error", 0), 0u) << malformed.output;
  std::filesystem::remove_all(dir);

  // view checks its scenario before it opens a window (a build without GLFW says so instead).
  const ProgramResult view = RunViqu("view /nonexistent/s.yaml");
  EXPECT_EQ(view.exit_code, 2);
  EXPECT_TRUE(view.output == "viqu: /nonexistent/s.yaml: file not found\n" ||
              view.output.find("built without the viewer") != std::string::npos)
      << view.output;
}

using testing::ReadAll;

// A TUM RGB-D sequence of three 64x48 frames of noise at 2 m, with its camera.yaml.
void WriteTinyTum(const std::string& dir) {
  std::filesystem::create_directories(dir + "/rgb");
  std::filesystem::create_directories(dir + "/depth");
  std::string rgb_txt, depth_txt;
  for (int i = 0; i < 3; ++i) {
    const std::string name = "1.0" + std::to_string(i) + "0000.png";  // 1.000000, 1.010000, 1.020000
    cv::Mat rgb(48, 64, CV_8UC3);
    cv::RNG(i + 1).fill(rgb, cv::RNG::UNIFORM, 0, 256);
    cv::imwrite(dir + "/rgb/" + name, rgb);
    cv::imwrite(dir + "/depth/" + name, cv::Mat(48, 64, CV_16U, cv::Scalar(10000)));
    rgb_txt += name.substr(0, 8) + " rgb/" + name + "\n";
    depth_txt += name.substr(0, 8) + " depth/" + name + "\n";
  }
  std::ofstream(dir + "/rgb.txt") << rgb_txt;
  std::ofstream(dir + "/depth.txt") << depth_txt;
  std::ofstream(dir + "/camera.yaml") << "fx: 50\nfy: 50\ncx: 31.5\ncy: 23.5\nwidth: 64\nheight: 48\n";
}

TEST(CliProgram, SlamTakesSettingsOverridesAndMasks) {
  if (!std::filesystem::exists(std::string(VIQU_BINARY_DIR) + "/apps/viqu")) {
    GTEST_SKIP() << "the viqu program is not built";
  }
  // An unknown or ill-typed key is bad input, reported before the dataset is looked at.
  const ProgramResult unknown = RunViqu("slam /nonexistent --set tracking.no_such_key=1");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.output.rfind("viqu: --set tracking.no_such_key=1: unknown key 'tracking.no_such_key'", 0), 0u)
      << unknown.output;
  const ProgramResult ill_typed = RunViqu("slam /nonexistent --set tracking.min_inliers=many");
  EXPECT_EQ(ill_typed.exit_code, 2);
  EXPECT_NE(ill_typed.output.find("'tracking.min_inliers' expected an integer"), std::string::npos) << ill_typed.output;
  // A valid key passes on to the dataset.
  const ProgramResult valid = RunViqu("slam /nonexistent --set tracking.min_inliers=40");
  EXPECT_EQ(valid.exit_code, 2);
  EXPECT_EQ(valid.output, "viqu: /nonexistent: dataset folder not found\n");

  const std::string dir = ::testing::TempDir() + "viqu_cli_slam";
  std::filesystem::remove_all(dir);
  WriteTinyTum(dir + "/tum");
  std::filesystem::create_directories(dir + "/masks");
  std::ofstream(dir + "/masks/instances.csv") << "#id,category,name\n3,person,alice\n";
  cv::Mat mask(48, 64, CV_16U, cv::Scalar(0));
  mask(cv::Rect(10, 10, 8, 8)).setTo(3);
  cv::imwrite(dir + "/masks/1.000000.png", mask);
  const std::string common = "slam " + dir + "/tum --format tum --masks " + dir + "/masks --out " + dir + "/out";
  const ProgramResult ok = RunViqu(common + " --set tracking.min_inliers=40 --set tracking.max_hamming=80");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const std::string settings = ReadAll(dir + "/out/slam_settings.yaml");
  EXPECT_NE(settings.find("min_inliers: 40\n"), std::string::npos) << settings;
  EXPECT_NE(settings.find("max_hamming: 80\n"), std::string::npos) << settings;
  EXPECT_NE(ReadAll(dir + "/out/metrics.json").find("\"masks\": \"" + dir + "/masks\""), std::string::npos);
  // The calibration in use is printed and recorded.
  EXPECT_NE(ok.output.find("camera " + dir + "/tum/camera.yaml: fx 50 fy 50 cx 31.5 cy 23.5, 64x48"), std::string::npos) << ok.output;
  EXPECT_NE(ReadAll(dir + "/out/metrics.json").find("\"calibration\": \"" + dir + "/tum/camera.yaml\""), std::string::npos);
  EXPECT_EQ(settings.rfind("# camera calibration: " + dir + "/tum/camera.yaml (fx 50, fy 50, cx 31.5, cy 23.5, 64x48)\n", 0), 0u)
      << settings;
  // --camera (an ORB-SLAM2 settings file) replaces the folder's calibration; without any, exit 2.
  std::ofstream(dir + "/orb.yaml") << "%YAML:1.0\nCamera.fx: 52\nCamera.fy: 52\nCamera.cx: 31.5\nCamera.cy: 23.5\n"
                                      "DepthMapFactor: 5000.0\nORBextractor.nFeatures: 1000\n";
  const ProgramResult orb = RunViqu(common + " --camera " + dir + "/orb.yaml");
  ASSERT_EQ(orb.exit_code, 0) << orb.output;
  EXPECT_NE(orb.output.find("(ORB-SLAM2 settings): fx 52 fy 52 cx 31.5 cy 23.5, 64x48"), std::string::npos) << orb.output;
  std::filesystem::remove(dir + "/tum/camera.yaml");
  const ProgramResult none = RunViqu(common);
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(none.output.rfind("viqu: " + dir + "/tum: no camera calibration", 0), 0u) << none.output;
  std::ofstream(dir + "/tum/camera.yaml") << "fx: 50\nfy: 50\ncx: 31.5\ncy: 23.5\nwidth: 64\nheight: 48\n";

  // A bad mask is bad input naming the file.
  cv::imwrite(dir + "/masks/1.010000.png", cv::Mat(48, 65, CV_16U, cv::Scalar(0)));
  const ProgramResult bad = RunViqu(common);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("viqu: " + dir + "/masks/1.010000.png: mask is 65x48, its image is 64x48"),
            std::string::npos)
      << bad.output;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace viqu::app

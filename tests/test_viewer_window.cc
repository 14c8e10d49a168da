// `viqu view` in a real window on a virtual display (Xvfb): it opens, shows the run, saves a
// screenshot whose camera panel is the run's camera image, closes with exit 0, and its run folder
// holds the same estimate as `viqu run`. Without a display it fails cleanly before writing
// anything. Skips (with the reason) where Xvfb is not installed.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/child_process.h"
#include "viqu_program.h"
#include "read_all.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;
using testing::RunViqu;

using testing::ReadAll;

const char* const kXvfb = "/usr/bin/Xvfb";

// An Xvfb server on a free display number (it picks one and reports it with -displayfd).
class VirtualDisplay {
 public:
  VirtualDisplay() {
    const fs::path log = fs::temp_directory_path() / "viqu_test_xvfb.log";
    pid_ = StartProcess({kXvfb, "-displayfd", "1", "-screen", "0", "1600x900x24", "-nolisten", "tcp"}, log.string());
    for (int i = 0; i < 100 && name_.empty(); ++i) {  // up to 10 s for the server to come up
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      std::istringstream in(ReadAll(log));
      for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.find_first_not_of("0123456789") == std::string::npos) name_ = ":" + line;
      }
    }
  }
  ~VirtualDisplay() {
    ::kill(pid_, SIGTERM);
    WaitProcess(pid_);
  }
  const std::string& name() const { return name_; }  // empty when the server did not start

 private:
  pid_t pid_ = -1;
  std::string name_;
};

const std::string kScenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
const char* const kXdotool = "/usr/bin/xdotool";

// Runs a shell command; its standard output.
std::string Shell(const std::string& cmd) {
  std::string out;
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return out;
  char buf[256];
  for (size_t n; (n = std::fread(buf, 1, sizeof(buf), p)) > 0;) out.append(buf, n);
  ::pclose(p);
  return out;
}

// Polls `probe` every 100 ms for up to `timeout_s`; whether it came true.
template <class F>
bool WaitFor(F probe, double timeout_s) {
  for (int i = 0; i < static_cast<int>(timeout_s * 10); ++i) {
    if (probe()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return probe();
}

TEST(ViewerWindow, WithoutADisplayFailsBeforeWritingAnything) {
  ASSERT_TRUE(testing::ViquBuilt());
  const fs::path out = fs::temp_directory_path() / "viqu_view_nodisplay";
  fs::remove_all(out);
  const std::string cmd = "env -u DISPLAY -u WAYLAND_DISPLAY " + testing::ViquBinary() + " view " + kScenario +
                          " --set duration_s=0.5 --exit-at-end --out " + out.string() + " 2>&1";
  std::FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string output;
  char buf[512];
  for (size_t n; (n = std::fread(buf, 1, sizeof(buf), p)) > 0;) output.append(buf, n);
  const int code = ExitCodeOf(::pclose(p));
  EXPECT_EQ(code, 1) << output;
  EXPECT_NE(output.find("viewer: cannot start GLFW"), std::string::npos) << output;
  EXPECT_NE(output.find("DISPLAY"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(out)) << "nothing is written when the window cannot open";
}

TEST(ViewerWindow, ShowsTheRunAndSavesAScreenshotUnderXvfb) {
  ASSERT_TRUE(testing::ViquBuilt());
  if (!fs::exists(kXvfb)) GTEST_SKIP() << kXvfb << " not found (Debian package xvfb): the window test needs a virtual display";
  VirtualDisplay display;
  ASSERT_FALSE(display.name().empty()) << "Xvfb did not report a display number";
  ::setenv("DISPLAY", display.name().c_str(), 1);

  const fs::path tmp = fs::temp_directory_path();
  const fs::path viewed = tmp / "viqu_view_window", plain = tmp / "viqu_view_plain";
  const fs::path shot = tmp / "viqu_view_window.png";
  fs::remove_all(viewed);
  fs::remove_all(plain);
  fs::remove(shot);
  const std::string sets = " --set duration_s=1.5";
  const testing::ProgramResult v = RunViqu("view " + kScenario + sets + " --speed 0 --exit-at-end --screenshot " +
                                           shot.string() + " --out " + viewed.string());
  ASSERT_EQ(v.exit_code, 0) << v.output;
  const testing::ProgramResult r = RunViqu("run " + kScenario + sets + " --record --out " + plain.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // The window shows the run; it does not change it.
  EXPECT_EQ(ReadAll(viewed / "trajectory_est.txt"), ReadAll(plain / "trajectory_est.txt"));
  EXPECT_EQ(ReadAll(viewed / "trajectory_gt.txt"), ReadAll(plain / "trajectory_gt.txt"));
  EXPECT_TRUE(fs::exists(viewed / "run_complete.json"));

  // The screenshot: the whole 1280 x 720 window.
  const cv::Mat s = cv::imread(shot.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(s.empty()) << shot;
  EXPECT_EQ(s.cols, 1280);
  EXPECT_EQ(s.rows, 720);
  // Its top-right 640 x 480 panel is the last camera image (the overlays aside): compare it with
  // the last left image that `viqu run --record` wrote.
  std::vector<fs::path> images;
  for (const auto& e : fs::directory_iterator(plain / "dataset" / "mav0" / "cam0" / "data")) images.push_back(e.path());
  ASSERT_FALSE(images.empty());
  std::sort(images.begin(), images.end(), [](const fs::path& a, const fs::path& b) {
    return std::stoll(a.stem().string()) < std::stoll(b.stem().string());  // named by time (ns)
  });
  const cv::Mat last = cv::imread(images.back().string(), cv::IMREAD_COLOR);
  ASSERT_EQ(last.cols, 640);
  ASSERT_EQ(last.rows, 480);
  const cv::Mat panel = s(cv::Rect(640, 0, 640, 480));
  cv::Mat diff, close;
  cv::absdiff(panel, last, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  cv::threshold(diff, close, 3, 255, cv::THRESH_BINARY_INV);
  const double same = cv::countNonZero(close) / static_cast<double>(close.total());
  // And against an earlier image: the panel is the frame of the end, not any frame.
  const cv::Mat first = cv::imread(images.front().string(), cv::IMREAD_COLOR);
  cv::absdiff(panel, first, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  cv::threshold(diff, close, 3, 255, cv::THRESH_BINARY_INV);
  const double same_first = cv::countNonZero(close) / static_cast<double>(close.total());
  std::printf("viewer screenshot: %.1f%% of the camera panel equals the last recorded image, %.1f%% the first\n",
              100 * same, 100 * same_first);
  EXPECT_GT(same, 0.5);  // measured 75.1% (the rest: feature marks, tinted masks, the status text)
  EXPECT_LT(same_first, same);  // measured 15.8%
  // The scene panel (left half) is a rendered world, not an empty clear colour.
  cv::Mat grey;
  cv::cvtColor(s(cv::Rect(0, 0, 640, 720)), grey, cv::COLOR_BGR2GRAY);
  cv::Scalar mean, stddev;
  cv::meanStdDev(grey, mean, stddev);
  std::printf("viewer screenshot: scene panel grey mean %.1f, std %.1f\n", mean[0], stddev[0]);
  EXPECT_GT(stddev[0], 23);  // measured 46.6 (a blank panel: 0)
}

// Keys as a user presses them (xdotool through the X server): three steps of a paused run show
// frames 1, 2 and 3; q closes the window, which ends the run there with the folder marked
// incomplete and exit 0.
TEST(ViewerWindow, KeysStepAPausedRunAndQuitEndsIt) {
  ASSERT_TRUE(testing::ViquBuilt());
  if (!fs::exists(kXvfb)) GTEST_SKIP() << kXvfb << " not found (Debian package xvfb): the window test needs a virtual display";
  if (!fs::exists(kXdotool)) GTEST_SKIP() << kXdotool << " not found (Debian package xdotool): the key test needs it";
  VirtualDisplay display;
  ASSERT_FALSE(display.name().empty()) << "Xvfb did not report a display number";
  ::setenv("DISPLAY", display.name().c_str(), 1);
  const fs::path tmp = fs::temp_directory_path();
  const fs::path out = tmp / "viqu_view_keys", shot = tmp / "viqu_view_keys.png", log = tmp / "viqu_view_keys.log";
  fs::remove_all(out);
  fs::remove(shot);
  const pid_t pid = testing::SpawnViqu({"view", kScenario, "--set", "duration_s=3", "--paused", "--screenshot",
                                        shot.string(), "--out", out.string()}, log.string());
  std::string window;
  const auto title = [&] { return Shell(std::string(kXdotool) + " getwindowname " + window + " 2>/dev/null"); };
  const bool opened = WaitFor([&] {
    window = Shell(std::string(kXdotool) + " search --name 'viqu view: static_room' 2>/dev/null");
    window = window.substr(0, window.find('\n'));
    return !window.empty() && title().find("t 0.000 s") != std::string::npos;  // frame 0 shown, paused
  }, 120);
  if (!opened) ::kill(pid, SIGTERM);
  ASSERT_TRUE(opened) << ReadAll(log);
  Shell(std::string(kXdotool) + " windowfocus --sync " + window + " key n n n");
  const bool stepped = WaitFor([&] { return title().find("t 0.150 s") != std::string::npos; }, 120);
  EXPECT_TRUE(stepped) << title();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_NE(title().find("t 0.150 s"), std::string::npos) << "paused: no frame after the three steps";
  Shell(std::string(kXdotool) + " windowfocus --sync " + window + " key q");
  int status = 0;
  const bool exited = WaitFor([&] { return ::waitpid(pid, &status, WNOHANG) == pid; }, 60);
  if (!exited) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  ASSERT_TRUE(exited) << "q did not close the viewer: " << ReadAll(log);
  EXPECT_EQ(ExitCodeOf(status), 0) << ReadAll(log);
  std::istringstream gt(ReadAll(out / "trajectory_gt.txt"));
  int poses = 0;
  for (std::string line; std::getline(gt, line);) poses += !line.empty() && line[0] != '#';
  EXPECT_EQ(poses, 4);  // frames 0 to 3
  EXPECT_FALSE(fs::exists(out / "run_complete.json"));
  EXPECT_NE(ReadAll(out / "run_incomplete.json").find("viewer closed at simulated time 0.150 s"), std::string::npos)
      << ReadAll(out / "run_incomplete.json");
  EXPECT_TRUE(fs::exists(shot));
}

}  // namespace
}  // namespace viqu

#pragma once
// `viqu view`: a window on a running scenario. The left side shows the world from a free camera
// that follows the robot, with the ground-truth (green), SLAM (orange) and leg-odometry (purple, mode full) camera paths and the
// map points (blue; red when created on a segmented object); the right side shows the left
// camera image with SLAM's overlays (runner/overlay_video.h) and a status panel. Keys: space
// pause, n or right arrow one frame, + and - speed, 1 real time, 0 as fast as it goes, f follow
// the robot, m map points on/off, q or Esc quit. Mouse: left drag orbits (shift: about the
// vertical), right drag pans, the wheel zooms.
#include <memory>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>
#include <opencv2/core/mat.hpp>

#include "runner/run_observer.h"
#include "viewer/playback.h"
#include "viewer/view_layout.h"

namespace viqu::viewer {

struct ViewerOptions {
  int width = 1280;          // window size (screen pixels)
  int height = 720;
  double speed = 1.0;        // simulated s per wall s; 0 = as fast as the run goes
  bool start_paused = false;
  bool exit_at_end = false;  // close when the run ends (else the window stays until closed)
  std::string screenshot_path;  // PNG of the window's last picture, written when the viewer ends
  std::string title = "viqu view";  // window title; the simulated time of the frame shown follows it
};

class ViewerWindow;
struct ViewerScene;

class RunViewer : public runner::RunObserver {
 public:
  // Opens the window; throws viqu::RunError without a display.
  explicit RunViewer(const ViewerOptions& opt);
  ~RunViewer() override;

  bool OnFrame(const runner::ObservedFrame& f) override;
  void OnRunEnd(const runner::ObservedFrame& last) override;

 private:
  // Applies queued input; true when the picture should change.
  bool HandleEvents(const mjModel* m);
  // Draws the window; `capture` (may be null) receives the picture (BGR) before it is shown.
  void Draw(const runner::ObservedFrame& f, const std::string& state, cv::Mat* capture = nullptr);
  // Writes the window's picture of `last` to opt_.screenshot_path (atomically), when asked for.
  void SaveScreenshot(const runner::ObservedFrame& last, const std::string& state);
  double NowS() const;

  ViewerOptions opt_;
  std::unique_ptr<ViewerWindow> window_;
  std::unique_ptr<ViewerScene> scene_;  // MuJoCo scene and render context, made at the first frame
  Playback playback_;
  bool follow_ = true;
  bool show_points_ = true;
  cv::Mat image_rgb_;  // the last camera image with overlays (RGB, unscaled)
  std::string track_text_, error_text_;
  double last_rtf_ = 0;  // simulated time over wall time across the last frames
  double rtf_t_s_ = -1, rtf_wall_s_ = 0;
  int draws_ = 0;  // pictures drawn (each camera frame once, plus redraws while paused or at the end)
  std::vector<double> draw_ms_;  // wall time of each picture (ms)
};

}  // namespace viqu::viewer

#include "viewer/run_viewer.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "runner/overlay_video.h"
#include "runner/slam_run.h"
#include "sim/world.h"
#include "viewer/map_geoms.h"
#include "viewer/viewer_window.h"

namespace viqu::viewer {
namespace {

// How long the viewer waits for input at a time while paused or waiting for a frame's turn (s):
// short enough for a responsive window, long enough not to spin.
constexpr double kPollS = 0.03;
// Extra geoms in the scene for paths and map points (each a few hundred bytes).
constexpr int kExtraGeoms = 6000;
// The free camera's start: high above the robot, looking down at it steeply, so that people in
// the room rarely hide the robot and the paths and the map show as on a floor plan.
constexpr double kCameraDistanceM = 4.0;
constexpr double kCameraElevationDeg = -65;
constexpr double kCameraAzimuthDeg = 200;
// Colours of the paths (RGBA).
constexpr float kTruthRgba[4] = {0.1f, 0.75f, 0.1f, 1};
constexpr float kEstimateRgba[4] = {1.0f, 0.5f, 0.0f, 1};
constexpr float kLegOdometryRgba[4] = {0.7f, 0.2f, 0.9f, 1};

}  // namespace

// The MuJoCo side of the window: scene, options, free camera and render context (in the
// window's GL context).
struct ViewerScene {
  explicit ViewerScene(const mjModel* m) {
    mjv_defaultScene(&scn);
    mjv_defaultOption(&vopt);
    mjv_defaultCamera(&cam);
    mjr_defaultContext(&con);
    mjv_makeScene(m, &scn, m->ngeom + kExtraGeoms);
    mjr_makeContext(m, &con, mjFONTSCALE_100);
    // Shadows and reflections each cost a scene pass in a software renderer and show little here.
    scn.flags[mjRND_SHADOW] = 0;
    scn.flags[mjRND_REFLECTION] = 0;
    cam.type = mjCAMERA_FREE;
    cam.distance = kCameraDistanceM;
    cam.elevation = kCameraElevationDeg;
    cam.azimuth = kCameraAzimuthDeg;
  }
  ~ViewerScene() {
    mjr_freeContext(&con);
    mjv_freeScene(&scn);
  }
  ViewerScene(const ViewerScene&) = delete;
  ViewerScene& operator=(const ViewerScene&) = delete;

  mjvScene scn;
  mjvOption vopt;
  mjvCamera cam;
  mjrContext con;
};

RunViewer::RunViewer(const ViewerOptions& opt)
    : opt_(opt),
      window_(std::make_unique<ViewerWindow>(opt.width, opt.height, opt.title)),
      playback_(opt.speed, opt.start_paused) {}

RunViewer::~RunViewer() {
  if (window_) window_->MakeCurrent();  // the render context is freed in the window's GL context
  scene_.reset();
}

double RunViewer::NowS() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool RunViewer::HandleEvents(const mjModel* m) {
  bool changed = false;
  for (const InputEvent& e : window_->TakeEvents()) {
    changed = true;
    switch (e.kind) {
      case InputEvent::Kind::kKey:
        switch (e.key) {
          case GLFW_KEY_SPACE: playback_.TogglePause(); break;
          case GLFW_KEY_N:
          case GLFW_KEY_RIGHT: playback_.Step(); break;
          case GLFW_KEY_EQUAL:
          case GLFW_KEY_KP_ADD: playback_.Faster(); break;
          case GLFW_KEY_MINUS:
          case GLFW_KEY_KP_SUBTRACT: playback_.Slower(); break;
          case GLFW_KEY_1: playback_.SetSpeed(1); break;
          case GLFW_KEY_0: playback_.SetSpeed(0); break;
          case GLFW_KEY_F: follow_ = !follow_; break;
          case GLFW_KEY_M: show_points_ = !show_points_; break;
          case GLFW_KEY_Q:
          case GLFW_KEY_ESCAPE: window_->RequestClose(); break;
          default: changed = false; break;
        }
        break;
      case InputEvent::Kind::kDrag: {
        if (!scene_) break;
        int action = mjMOUSE_ROTATE_V;
        if (e.button == 0) action = e.shift ? mjMOUSE_ROTATE_H : mjMOUSE_ROTATE_V;
        if (e.button == 1) {
          action = e.shift ? mjMOUSE_MOVE_H : mjMOUSE_MOVE_V;
          follow_ = false;  // a pan leaves the robot; f follows it again
        }
        if (e.button == 2) action = mjMOUSE_ZOOM;
        mjv_moveCamera(m, action, e.dx, e.dy, &scene_->scn, &scene_->cam);
        break;
      }
      case InputEvent::Kind::kScroll:
        if (scene_) mjv_moveCamera(m, mjMOUSE_ZOOM, 0, -0.05 * e.dy, &scene_->scn, &scene_->cam);
        break;
    }
  }
  return changed;
}

bool RunViewer::OnFrame(const runner::ObservedFrame& f) {
  const mjModel* m = f.world->model();
  window_->MakeCurrent();
  if (!scene_) scene_ = std::make_unique<ViewerScene>(m);

  // What the frame shows, kept for redraws while paused and after the run.
  cv::Mat bgr = runner::OverlayVideo::Draw(*f.frame, f.track, -1);
  cv::cvtColor(bgr, image_rgb_, cv::COLOR_BGR2RGB);
  track_text_ = f.track ? std::string(slam::TrackStatusName(f.track->status)) + ", " +
                              std::to_string(f.track->inliers) + " inliers, " +
                              std::to_string(f.track->features) + " features"
                        : "no SLAM (--no-slam)";
  error_text_.clear();
  if (f.track && f.ground_truth && !f.ground_truth->empty()) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.1f mm", 1e3 * (f.track->T_w_c.translation() - f.ground_truth->back().p_w_x).norm());
    error_text_ = buf;
  }
  // The speed achieved between two frames shown without a pause between them.
  const double now = NowS();
  if (playback_.paused()) {
    rtf_t_s_ = -1;
    last_rtf_ = 0;
  } else {
    if (rtf_t_s_ >= 0 && now > rtf_wall_s_) last_rtf_ = (f.t_s - rtf_t_s_) / (now - rtf_wall_s_);
    rtf_t_s_ = f.t_s;
    rtf_wall_s_ = now;
  }

  // Wait for the frame's turn at the chosen speed, answering the window meanwhile.
  for (;;) {
    window_->PollEvents();
    HandleEvents(m);
    if (window_->CloseRequested()) return false;
    if (playback_.paused()) break;
    const double wait = playback_.WaitBefore(f.t_s, NowS());
    if (wait <= 0) break;
    window_->PollEvents(std::min(wait, kPollS));
  }
  Draw(f, "");
  char title[64];
  std::snprintf(title, sizeof(title), " - t %.3f s", f.t_s);
  window_->SetTitle(opt_.title + title);
  // Paused: hold this frame (the camera still moves) until resumed or stepped.
  while (!playback_.TakeFrame()) {
    window_->PollEvents(kPollS);
    const bool changed = HandleEvents(m);
    if (window_->CloseRequested()) return false;
    if (changed) Draw(f, "");
  }
  return true;
}

void RunViewer::OnRunEnd(const runner::ObservedFrame& last) {
  if (!scene_ || last.world == nullptr) return;  // no frame was ever shown
  window_->MakeCurrent();
  const mjModel* m = last.world->model();
  const char* state = window_->CloseRequested() ? "run ended (window closed)" : "run finished";
  Draw(last, state);
  window_->SetTitle(opt_.title + " - " + state);
  if (!opt_.exit_at_end) {
    while (!window_->CloseRequested()) {
      window_->PollEvents(kPollS * 3);
      if (HandleEvents(m)) Draw(last, state);
    }
  }
  SaveScreenshot(last, state);
  std::vector<double> ms = draw_ms_;
  if (!ms.empty()) {
    std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
    std::printf("viewer: %d pictures drawn, %.1f ms median each\n", draws_, ms[ms.size() / 2]);
  }
}

void RunViewer::Draw(const runner::ObservedFrame& f, const std::string& state, cv::Mat* capture) {
  const double t0 = NowS();
  window_->MakeCurrent();
  int fb_w = 0, fb_h = 0;
  window_->FramebufferSize(&fb_w, &fb_h);
  const ViewLayout layout = LayoutFor(fb_w, fb_h, image_rgb_.cols, image_rgb_.rows);
  mjvScene& scn = scene_->scn;
  mjvCamera& cam = scene_->cam;
  const GroundTruthState gt = f.world->GroundTruth();
  if (follow_) {
    for (int i = 0; i < 3; ++i) cam.lookat[i] = gt.T_w_body.p_w_x[i];
  }
  // mjv_updateScene only reads the simulation state; MuJoCo's C API has no const overload.
  mjv_updateScene(f.world->model(), const_cast<mjData*>(f.world->data()), &scene_->vopt, nullptr, &cam, mjCAT_ALL,
                  &scn);
  MapDrawing drawing;
  if (f.ground_truth) {
    MapDrawing::Path truth;
    for (const StampedPose& p : *f.ground_truth) truth.points.push_back(p.p_w_x);
    std::copy(kTruthRgba, kTruthRgba + 4, truth.rgba);
    drawing.paths.push_back(std::move(truth));
  }
  if (f.leg_odometry) {
    MapDrawing::Path lo;
    for (const StampedPose& p : *f.leg_odometry) lo.points.push_back(p.p_w_x);
    std::copy(kLegOdometryRgba, kLegOdometryRgba + 4, lo.rgba);
    drawing.paths.push_back(std::move(lo));
  }
  int map_points = 0, keyframes = 0;
  if (f.slam) {
    MapDrawing::Path est;
    for (const StampedPose& p : f.slam->estimate()) est.points.push_back(p.p_w_x);
    std::copy(kEstimateRgba, kEstimateRgba + 4, est.rgba);
    drawing.paths.push_back(std::move(est));
    const std::vector<slam::SlamSystem::MapPointInfo> points = f.slam->system().MapPoints();
    map_points = static_cast<int>(points.size());
    keyframes = static_cast<int>(f.slam->system().KeyFrames().size());
    if (show_points_) {
      for (const auto& p : points) {
        drawing.map_points.push_back(p.p_w);
        drawing.on_object.push_back(p.object != 0);
      }
    }
  }
  AddMapGeoms(drawing, MapStyle(), &scn);

  mjrContext& con = scene_->con;
  mjr_setBuffer(mjFB_WINDOW, &con);
  const mjrRect full{0, 0, fb_w, fb_h};
  mjr_rectangle(full, 0.12f, 0.12f, 0.14f, 1);
  const mjrRect scene_rect{layout.scene.left, layout.scene.bottom, layout.scene.width, layout.scene.height};
  mjr_render(scene_rect, &scn, &con);
  mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, scene_rect,
              "space pause   n step   + - speed   1 real time   0 fastest   f follow   m map points   q quit\n"
              "mouse: left orbit (shift: turn), right pan, wheel zoom",
              nullptr, &con);

  if (layout.image_scale > 0 && !image_rgb_.empty()) {
    cv::Mat shown;
    if (layout.image.width != image_rgb_.cols || layout.image.height != image_rgb_.rows) {
      cv::resize(image_rgb_, shown, cv::Size(layout.image.width, layout.image.height), 0, 0, cv::INTER_AREA);
    } else {
      shown = image_rgb_.clone();
    }
    cv::flip(shown, shown, 0);  // GL rows go bottom-up
    if (!shown.isContinuous()) shown = shown.clone();
    const mjrRect image_rect{layout.image.left, layout.image.bottom, layout.image.width, layout.image.height};
    mjr_drawPixels(shown.data, nullptr, image_rect, &con);
  }

  char speed[32];
  if (playback_.speed() == 0) {
    std::snprintf(speed, sizeof(speed), "fastest");
  } else {
    std::snprintf(speed, sizeof(speed), "%gx", playback_.speed());
  }
  char left[512], right[512];
  std::snprintf(left, sizeof(left), "time\nspeed\nachieved\ntracking\nerror\nmap\n%s", state.empty() ? "" : "state");
  char achieved[32] = "-";
  if (last_rtf_ > 0) std::snprintf(achieved, sizeof(achieved), "%.2fx real time", last_rtf_);
  std::snprintf(right, sizeof(right), "%.2f s of %.1f s\n%s%s\n%s\n%s\n%s\n%d points, %d keyframes\n%s",
                f.t_s, f.duration_s, speed, playback_.paused() ? " (paused)" : "", achieved, track_text_.c_str(),
                error_text_.empty() ? "-" : error_text_.c_str(), map_points, keyframes, state.c_str());
  const mjrRect status_rect{layout.status.left, layout.status.bottom, layout.status.width, layout.status.height};
  mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, status_rect, left, right, &con);
  if (capture) *capture = window_->ReadBackBuffer();
  window_->SwapBuffers();
  ++draws_;
  draw_ms_.push_back(1e3 * (NowS() - t0));
}

void RunViewer::SaveScreenshot(const runner::ObservedFrame& last, const std::string& state) {
  if (opt_.screenshot_path.empty()) return;
  // Draw the picture once more and read it before the swap: the back buffer is the one a window
  // surface reliably lets us read.
  cv::Mat bgr;
  Draw(last, state, &bgr);
  std::vector<uchar> png;
  if (!cv::imencode(".png", bgr, png)) throw RunError("viewer: cannot encode the screenshot as PNG");
  WriteFileAtomic(opt_.screenshot_path, std::string(png.begin(), png.end()));
}

}  // namespace viqu::viewer

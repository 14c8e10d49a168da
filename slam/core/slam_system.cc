#include "slam/core/slam_system.h"

#include <chrono>

#include "common/errors.h"
#include "slam/core/local_mapper.h"
#include "slam/core/map.h"
#include "slam/core/tracker.h"

namespace viqu::slam {

const char* TrackStatusName(TrackStatus s) {
  switch (s) {
    case TrackStatus::kInitialised: return "initialised";
    case TrackStatus::kTracking: return "tracking";
    case TrackStatus::kRelocalised: return "relocalised";
    case TrackStatus::kLost: return "lost";
  }
  return "unknown";
}

struct SlamSystem::Impl {
  Impl(const SlamSettings& s, const Eigen::Isometry3d& T0) : settings(s), world_from_map(T0), tracker(s, &map) {}

  SlamSettings settings;
  Eigen::Isometry3d world_from_map;
  Map map;
  Tracker tracker;
  std::unique_ptr<LocalMapper> mapper;
  SlamStats stats;
};

SlamSystem::SlamSystem(const SlamSettings& settings, const Eigen::Isometry3d& world_from_first_camera)
    : impl_(std::make_unique<Impl>(settings, world_from_first_camera)) {}

SlamSystem::~SlamSystem() {
  // The mapping thread must stop before the map goes.
  if (impl_) impl_->mapper.reset();
}

TrackResult SlamSystem::Track(const StereoFrame& frame) {
  const auto t0 = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  const bool rgbd = m.settings.input == "rgbd";
  if (frame.left_rgb.empty()) throw InputError("frame at t=" + std::to_string(frame.t_ns) + " ns has no left image");
  if (rgbd ? frame.left_depth_m.empty() : frame.right_rgb.empty()) {
    throw InputError("frame at t=" + std::to_string(frame.t_ns) + " ns has no " + (rgbd ? "depth image" : "right image") +
                     " (input: " + m.settings.input + ")");
  }
  if (!m.tracker.HasCamera()) {
    if (frame.intrinsics.fx <= 0 || frame.intrinsics.width <= 0 || (!rgbd && frame.baseline_m <= 0)) {
      throw InputError("the first frame has no valid intrinsics or baseline");
    }
    m.tracker.SetCamera(frame);
    m.mapper = std::make_unique<LocalMapper>(m.tracker.camera(), m.settings, &m.map);
  }
  TrackResult r = m.tracker.Track(frame, m.mapper.get());
  r.track_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // Mapping after the keyframe: inline in sync mode (not counted as tracking time), queued in
  // realtime mode.
  if (KeyFrame* kf = m.tracker.TakePendingKeyFrame()) m.mapper->Insert(kf);
  r.T_w_c = m.world_from_map * r.T_w_c;
  ++m.stats.frames;
  if (r.status == TrackStatus::kLost) ++m.stats.lost_frames;
  if (r.status == TrackStatus::kRelocalised) ++m.stats.relocalisations;
  m.stats.track_ms.push_back(r.track_ms);
  return r;
}

void SlamSystem::Finish() {
  if (impl_->mapper) impl_->mapper->WaitIdle();
}

SlamStats SlamSystem::Stats() const {
  SlamStats s = impl_->stats;
  std::lock_guard<std::mutex> lock(impl_->map.mutex);
  s.keyframes = impl_->map.GoodKeyFrames();
  s.map_points = impl_->map.GoodPoints();
  if (impl_->mapper) s.local_ba_ms = impl_->mapper->ba_ms();
  return s;
}

const SlamSettings& SlamSystem::settings() const { return impl_->settings; }

}  // namespace viqu::slam

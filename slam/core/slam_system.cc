#include "slam/core/slam_system.h"

#include <algorithm>
#include <chrono>

#include "common/errors.h"
#include "slam/core/local_mapper.h"
#include "slam/core/map.h"
#include "slam/core/tracker.h"

namespace viqu::slam {
namespace {

// Frames between two Map::Reclaim calls. Housekeeping, not a decision: freeing culled objects
// changes no result, only how long they stay allocated (about a second at 20 Hz).
constexpr int kReclaimEveryFrames = 20;

}  // namespace

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
  std::unique_ptr<DynamicObjects> dynamic;
  SlamStats stats;
  bool record_features = false;  // fill TrackResult::marks
};

SlamSystem::SlamSystem(const SlamSettings& settings, const Eigen::Isometry3d& world_from_first_camera)
    : impl_(std::make_unique<Impl>(settings, world_from_first_camera)) {}

SlamSystem::~SlamSystem() {
  // The mapping thread must stop before the map goes.
  if (impl_) impl_->mapper.reset();
}

void SlamSystem::SetMotionPrior(const Eigen::Isometry3d& T_cur_last, double sigma_m) {
  impl_->tracker.SetMotionPrior(T_cur_last, sigma_m);
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
  // Image types and sizes are checked here: the extractor and the stereo matcher index the
  // images by the first frame's size and read them as 8-bit grey or RGB and 32-bit depth.
  const auto describe = [](const cv::Mat& m) {
    return std::to_string(m.cols) + "x" + std::to_string(m.rows) + " with " + std::to_string(m.channels()) +
           " channel(s) of " + std::to_string(m.elemSize1() * 8) + " bits";
  };
  const std::string at = "frame at t=" + std::to_string(frame.t_ns) + " ns: ";
  if (frame.left_rgb.type() != CV_8UC3 && frame.left_rgb.type() != CV_8UC1) {
    throw InputError(at + "the left image must be 8-bit RGB or grey, got " + describe(frame.left_rgb));
  }
  const cv::Size size = frame.left_rgb.size();
  if (size.width != frame.intrinsics.width || size.height != frame.intrinsics.height) {
    throw InputError(at + "the left image is " + describe(frame.left_rgb) + ", the intrinsics say " +
                     std::to_string(frame.intrinsics.width) + "x" + std::to_string(frame.intrinsics.height));
  }
  if (!frame.right_rgb.empty() && (frame.right_rgb.type() != frame.left_rgb.type() || frame.right_rgb.size() != size)) {
    throw InputError(at + "the right image (" + describe(frame.right_rgb) + ") differs from the left (" +
                     describe(frame.left_rgb) + ")");
  }
  if (!frame.left_depth_m.empty() && (frame.left_depth_m.type() != CV_32FC1 || frame.left_depth_m.size() != size)) {
    throw InputError(at + "the depth image must be 32-bit float metres of the left image's size, got " +
                     describe(frame.left_depth_m));
  }
  if (!frame.left_instance_id.empty() && (frame.left_instance_id.type() != CV_16UC1 || frame.left_instance_id.size() != size)) {
    throw InputError(at + "the instance mask must be 16-bit ids of the left image's size, got " +
                     describe(frame.left_instance_id));
  }
  if (!m.tracker.HasCamera()) {
    if (frame.intrinsics.fx <= 0 || frame.intrinsics.width <= 0 || (!rgbd && frame.baseline_m <= 0)) {
      throw InputError("the first frame has no valid intrinsics or baseline");
    }
    m.tracker.SetCamera(frame);
    m.mapper = std::make_unique<LocalMapper>(m.tracker.camera(), m.settings, &m.map);
    m.dynamic = std::make_unique<DynamicObjects>(m.settings, m.tracker.camera());
  }
  // Free the culled keyframes and map points that nothing holds any more (Map::Reclaim), once a
  // second at 20 Hz: a long run's memory stays bounded, and the results are the same.
  if (m.stats.frames % kReclaimEveryFrames == 0) {
    std::lock_guard<std::mutex> lock(m.map.mutex);
    std::vector<const KeyFrame*> pinned_keyframes;
    std::vector<const MapPoint*> pinned_points;
    if (m.mapper->PinnedIfIdle(&pinned_keyframes, &pinned_points)) {
      m.tracker.Pinned(&pinned_keyframes, &pinned_points);
      m.map.Reclaim(pinned_keyframes, pinned_points);
    }
  }
  using Clock = std::chrono::steady_clock;
  auto ms_since = [](Clock::time_point a) { return std::chrono::duration<double, std::milli>(Clock::now() - a).count(); };
  const std::shared_ptr<FrameFeatures> features = m.tracker.ExtractFeatures(frame);

  // Dynamic objects, before tracking: the features of objects judged dynamic go.
  auto td = Clock::now();
  const std::vector<bool> keep = m.dynamic->KeepMask(*features, frame.instances);
  int kept = static_cast<int>(std::count(keep.begin(), keep.end(), true));
  std::vector<bool> dropped_after;  // per feature: kept for tracking, then taken out of the pose
  std::shared_ptr<const FrameFeatures> tracked = features;
  if (kept < static_cast<int>(keep.size())) tracked = features->Subset(keep, m.tracker.camera().width, m.tracker.camera().height);
  double dynamic_ms = ms_since(td);

  TrackResult r = m.tracker.Track(frame, tracked, m.mapper.get());

  // After tracking: judge the objects again with the frame's pose (in a world frame that has
  // jumped if the frame was relocalised or began a new segment).
  td = Clock::now();
  if (r.status == TrackStatus::kRelocalised || r.status == TrackStatus::kInitialised) {
    m.dynamic->RestartMeasurements();
  }
  if (m.dynamic->method() != DynamicMethod::kNone && r.status != TrackStatus::kLost && !m.dynamic->reports().empty()) {
    Eigen::Isometry3d T_c_w = m.tracker.LastPose();
    const Eigen::Isometry3d T_c_w_tracked = T_c_w;
    if (m.dynamic->NeedsPose()) {
      std::vector<bool> movable(static_cast<size_t>(m.dynamic->reports().back().id) + 1, false);
      for (const ObjectReport& o : m.dynamic->reports()) movable[o.id] = true;
      T_c_w = m.tracker.LastPoseWithout(movable, m.settings.dynamic.adaptive.static_pose_min_share,
                                        m.settings.dynamic.adaptive.static_pose_outliers == 1, &r.excluded_share);
    }
    const std::vector<Eigen::Vector3d> points =
        m.dynamic->NeedsMapPoints() ? m.tracker.LocalMapPointPositions() : std::vector<Eigen::Vector3d>{};
    const std::vector<uint16_t> turned = m.dynamic->Update(frame.t_ns, *features, frame.left_instance_id, T_c_w, points, &T_c_w_tracked);
    if (!turned.empty()) {
      // The objects judged dynamic on this frame leave its pose too, not only the next frames':
      // their features go as if they had been dropped before tracking.
      std::vector<bool> excluded(static_cast<size_t>(*std::max_element(turned.begin(), turned.end())) + 1, false);
      for (uint16_t id : turned) excluded[id] = true;
      if (m.tracker.ReposeWithout(excluded, r.status == TrackStatus::kTracking)) {
        r.T_w_c = m.tracker.LastPose().inverse();
        m.dynamic->DropFromFrame(turned);
        dropped_after.assign(features->size(), false);
        for (size_t i = 0; i < features->size(); ++i) {
          const uint16_t id = features->object[i];
          if (keep[i] && id < excluded.size() && excluded[id]) {
            dropped_after[i] = true;
            --kept;
          }
        }
      }
    }
    // Only a confirmed decision culls the object's map points: a tentative one may be a single
    // mismatched look of an object that stands. What its points saw before it can have started
    // to move stays for BA (dynamic.keep_past_observations).
    if (!m.dynamic->JustConfirmed().empty()) {
      std::lock_guard<std::mutex> lock(m.map.mutex);
      for (uint16_t id : m.dynamic->JustConfirmed()) {
        const int64_t onset_ns = m.settings.dynamic.keep_past_observations ? m.dynamic->MotionOnsetNs(id) : kUndatedMotion;
        int retired = 0;
        m.stats.object_points_erased += m.map.RetireObjectPoints(id, onset_ns, &retired);
        m.stats.object_points_retired += retired;
      }
    }
  }
  dynamic_ms += ms_since(td);
  r.features = static_cast<int>(features->size());
  r.stereo_points = static_cast<int>(std::count_if(features->depth.begin(), features->depth.end(), [](float d) { return d > 0; }));
  r.features_dropped = r.features - kept;
  r.objects = m.dynamic->reports();
  if (m.record_features) {
    const std::vector<uint8_t>& fates = m.tracker.LastFeatureFates();
    r.marks.reserve(features->size());
    size_t j = 0;  // index among the tracked (kept) features
    for (size_t i = 0; i < features->size(); ++i) {
      FeatureMark mark;
      mark.x = features->keypoints[i].pt.x;
      mark.y = features->keypoints[i].pt.y;
      if (!keep[i]) {
        mark.fate = FeatureFate::kDropped;
      } else {
        const uint8_t f = j < fates.size() ? fates[j] : 0;
        mark.fate = f == 2 ? FeatureFate::kNew : f == 1 ? FeatureFate::kTracked : FeatureFate::kUnmatched;
        if (!dropped_after.empty() && dropped_after[i]) mark.fate = FeatureFate::kDropped;
        ++j;
      }
      r.marks.push_back(mark);
    }
  }
  r.dynamic_ms = dynamic_ms;
  r.track_ms = ms_since(t0);
  // Mapping after the keyframe: inline in sync mode (not counted as tracking time), queued in
  // realtime mode.
  if (KeyFrame* kf = m.tracker.TakePendingKeyFrame()) m.mapper->Insert(kf);
  r.T_w_c = m.world_from_map * r.T_w_c;
  ++m.stats.frames;
  if (r.status == TrackStatus::kLost) ++m.stats.lost_frames;
  if (r.status == TrackStatus::kRelocalised) ++m.stats.relocalisations;
  m.stats.track_ms.push_back(r.track_ms);
  m.stats.dynamic_ms.push_back(r.dynamic_ms);
  return r;
}

void SlamSystem::SetRecordFeatures(bool on) { impl_->record_features = on; }

void SlamSystem::Finish() {
  if (impl_->mapper) impl_->mapper->WaitIdle();
}

SlamStats SlamSystem::Stats() const {
  SlamStats s = impl_->stats;
  std::lock_guard<std::mutex> lock(impl_->map.mutex);
  s.keyframes = impl_->map.GoodKeyFrames();
  s.map_points = impl_->map.GoodPoints();
  s.keyframes_freed = impl_->map.keyframes_freed();
  s.map_points_freed = impl_->map.points_freed();
  s.keyframes_held = static_cast<int64_t>(impl_->map.keyframes().size());
  s.map_points_held = static_cast<int64_t>(impl_->map.points().size());
  s.map_heap_bytes = impl_->map.HeapBytes();
  if (impl_->mapper) s.local_ba_ms = impl_->mapper->ba_ms();
  return s;
}

std::vector<SlamSystem::KeyFrameInfo> SlamSystem::KeyFrames() const {
  std::lock_guard<std::mutex> lock(impl_->map.mutex);
  std::vector<KeyFrameInfo> out;
  for (const auto& kf : impl_->map.keyframes()) {
    if (kf->bad) continue;
    out.push_back({kf->t_ns, impl_->world_from_map * kf->T_c_w.inverse(), kf->fixed});
  }
  return out;
}

std::vector<SlamSystem::MapPointInfo> SlamSystem::MapPoints() const {
  std::lock_guard<std::mutex> lock(impl_->map.mutex);
  std::vector<MapPointInfo> out;
  out.reserve(impl_->map.points().size());
  for (const auto& p : impl_->map.points()) {
    if (p->bad) continue;
    out.push_back({impl_->world_from_map * p->p_w, p->object});
  }
  return out;
}

const SlamSettings& SlamSystem::settings() const { return impl_->settings; }

}  // namespace viqu::slam

#include "slam/core/tracker.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <map>
#include <set>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"
#include "slam/core/local_mapper.h"
#include "slam/core/map.h"

namespace viqu::slam {
namespace {

// Decision constants are tracking.* settings (slam/config/default.yaml). What stays here is
// ORB-SLAM's (Mur-Artal et al. 2015, 2017) with its reason.
// Relocalisation: up to 15 most recent keyframes and up to 30 candidates in all; PnP RANSAC with
// 200 iterations, a 4 px gate and 0.99 confidence; a candidate's neighbourhood is its 10 best
// covisible keyframes, searched with a 10 px window (the pose is good by then).
constexpr size_t kRelocRecentKeyframes = 15, kRelocCandidates = 30, kRelocNeighbours = 10;
constexpr int kRelocRansacIterations = 200;
constexpr float kRelocRansacPx = 4.0f;
constexpr double kRelocRansacConfidence = 0.99, kRelocSearchPx = 10.0;
// Descriptor matches and pose inliers below which a keyframe (as reference or relocalisation
// candidate) is not worth a pose optimisation: 15 matches, 10 inliers (ORB-SLAM's values; below
// them a 6-dof pose is not determined reliably).
constexpr int kMinDescriptorMatches = 15, kMinPoseInliers = 10;
// ORB-SLAM's keyframe rules: condition c1c (tracked < 25% of the reference's points) and c2's
// floor of 15 inliers; after a relocalisation no keyframe while the map holds more than 20.
constexpr double kKeyframeLowShare = 0.25;
constexpr int kKeyframeMinFloor = 15, kRelocNoKeyframeMapSize = 20;

MatcherOptions TrackerMatcherOptions(const SlamSettings& s) {
  MatcherOptions m;
  m.max_hamming = s.tracking.max_hamming;
  m.ratio = s.tracking.match_ratio;
  return m;
}

cv::Mat ToGrey(const cv::Mat& rgb) {
  cv::Mat grey;
  if (rgb.channels() == 3) {
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  } else {
    grey = rgb;
  }
  return grey;
}

}  // namespace

Tracker::Tracker(const SlamSettings& settings, Map* map)
    : settings_(settings), map_(map), extractor_(settings.orb), right_extractor_(settings.orb), stereo_(settings.stereo) {
  pose_opt_.rounds = settings.tracking.pose_iterations;
  pose_opt_.huber_px = settings.tracking.huber_px;
}

Tracker::~Tracker() = default;

void Tracker::SetCamera(const StereoFrame& frame) {
  const PinholeIntrinsics& k = frame.intrinsics;
  cam_.width = k.width;
  cam_.height = k.height;
  cam_.fx = k.fx;
  cam_.fy = k.fy;
  cam_.cx = k.cx;
  cam_.cy = k.cy;
  const bool rgbd = settings_.input == "rgbd";
  const double baseline = rgbd ? settings_.rgbd_virtual_baseline_m : frame.baseline_m;
  cam_.bf = k.fx * baseline;
  cam_.close_depth_m = settings_.stereo.max_depth_baselines * baseline;
  if (rgbd) cam_.close_depth_m = std::min(cam_.close_depth_m, settings_.rgbd_max_depth_m);
  // Stereo input only: an RGB-D camera's depth is measured, not matched (docs/MEASURED.md "Near
  // stereo, session 41").
  cam_.mono_below_depth_m = rgbd ? 0 : settings_.stereo.near_mono_baselines * baseline;
  cam_.near_right_scale = std::sqrt(settings_.stereo.near_right_weight_tracking);
  matcher_ = std::make_unique<Matcher>(cam_, TrackerMatcherOptions(settings_));
  have_camera_ = true;
}

std::shared_ptr<FrameFeatures> Tracker::ExtractFeatures(const StereoFrame& frame) const {
  if (frame.intrinsics.width != cam_.width || frame.intrinsics.height != cam_.height ||
      frame.intrinsics.fx != cam_.fx) {
    throw InputError("frame at t=" + std::to_string(frame.t_ns) + " ns has intrinsics that differ from the first frame's");
  }
  if (!frame.left_instance_id.empty() &&
      (frame.left_instance_id.cols != cam_.width || frame.left_instance_id.rows != cam_.height ||
       frame.left_instance_id.type() != CV_16UC1)) {
    throw InputError("frame at t=" + std::to_string(frame.t_ns) + " ns: the instance image is not " +
                     std::to_string(cam_.width) + "x" + std::to_string(cam_.height) + " 16-bit");
  }
  auto f = std::make_shared<FrameFeatures>();
  const bool rgbd = settings_.input == "rgbd";
  const cv::Mat left = ToGrey(frame.left_rgb);
  std::vector<cv::KeyPoint> lk;
  if (rgbd) {
    extractor_.Extract(left, cv::Mat(), &lk, &f->descriptors);
    f->keypoints = ToFeaturePoints(lk);
    f->u_right.assign(f->size(), -1.f);
    f->depth.assign(f->size(), -1.f);
    for (size_t i = 0; i < f->size(); ++i) {
      const int u = static_cast<int>(std::lround(f->keypoints[i].pt.x));
      const int v = static_cast<int>(std::lround(f->keypoints[i].pt.y));
      if (u < 0 || v < 0 || u >= frame.left_depth_m.cols || v >= frame.left_depth_m.rows) continue;
      const float d = frame.left_depth_m.at<float>(v, u);
      if (!(d > 0.05f) || d > settings_.rgbd_max_depth_m) continue;
      f->depth[i] = d;
      f->u_right[i] = static_cast<float>(f->keypoints[i].pt.x - cam_.bf / d);
    }
  } else {
    const cv::Mat right = ToGrey(frame.right_rgb);
    std::vector<cv::KeyPoint> rk;
    cv::Mat rd;
    // The right image's features on a second thread: the two extractions are independent.
    auto right_job = std::async(std::launch::async, [&] { right_extractor_.Extract(right, cv::Mat(), &rk, &rd); });
    extractor_.Extract(left, cv::Mat(), &lk, &f->descriptors);
    right_job.get();
    const auto sm = stereo_.Match(left, right, lk, f->descriptors, rk, rd, cam_.fx, cam_.bf / cam_.fx);
    f->keypoints = ToFeaturePoints(lk);
    f->u_right.assign(f->size(), -1.f);
    f->depth.assign(f->size(), -1.f);
    for (size_t i = 0; i < f->size(); ++i) {
      if (sm[i].u_right < 0) continue;
      const double disparity = f->keypoints[i].pt.x - sm[i].u_right;
      if (disparity <= 0) continue;
      const double depth = cam_.bf / disparity;
      if (depth < settings_.stereo.min_depth_m) continue;
      f->u_right[i] = sm[i].u_right;
      f->depth[i] = static_cast<float>(depth);
    }
  }
  const int levels = settings_.orb.num_levels;
  for (int l = 0; l < levels; ++l) {
    const double s = extractor_.ScaleOfLevel(l);
    f->level_scale.push_back(static_cast<float>(s));
    f->level_sigma2.push_back(static_cast<float>(s * s));
  }
  f->LabelObjects(frame.left_instance_id);
  f->BuildGrid(cam_.width, cam_.height);
  return f;
}

int Tracker::DropInstanceMatches(const std::vector<bool>& excluded_instance, Frame* f, int* matched) const {
  int excluded = 0;
  *matched = 0;
  for (size_t i = 0; i < f->size(); ++i) {
    if (!f->points[i] || f->points[i]->bad) continue;
    ++*matched;
    const uint16_t id = f->features->object[i];
    if (id < excluded_instance.size() && excluded_instance[id]) {
      f->points[i] = nullptr;
      ++excluded;
    }
  }
  return excluded;
}

void Tracker::RememberOutliers(const Frame& f) {
  last_outliers_.assign(f.size(), nullptr);
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.points[i] && f.outlier[i]) last_outliers_[i] = f.points[i];
  }
}

int Tracker::RestoreOutliersOutside(const std::vector<bool>& excluded_instance, Frame* f) const {
  if (last_outliers_.size() != f->size()) return 0;
  int restored = 0;
  for (size_t i = 0; i < f->size(); ++i) {
    MapPoint* p = last_outliers_[i];
    if (!p || !p->Matchable() || f->points[i]) continue;
    const uint16_t id = f->features->object[i];
    if (id < excluded_instance.size() && excluded_instance[id]) continue;
    f->points[i] = p;
    f->outlier[i] = false;
    ++restored;
  }
  return restored;
}

Eigen::Isometry3d Tracker::LastPoseWithout(const std::vector<bool>& excluded_instance, double min_share,
                                           bool with_outliers, double* excluded_share) {
  if (excluded_share) *excluded_share = 0;
  std::lock_guard<std::mutex> lock(map_->mutex);
  if (!last_.features) return last_.T_c_w;
  Frame f = last_;
  int inliers = 0;
  const int excluded = DropInstanceMatches(excluded_instance, &f, &inliers);
  if (inliers == 0 || excluded == 0) return last_.T_c_w;
  const double share = static_cast<double>(excluded) / inliers;
  if (excluded_share) *excluded_share = share;
  if (share < min_share) return last_.T_c_w;
  if (inliers - excluded < settings_.tracking.min_inliers) return last_.T_c_w;
  // A moving object that carries most of the matches drags the tracked pose along, which then
  // rejects much of the static scene as outliers (pushed_box at seed 2: the crate, 800 of 1200
  // features, was never judged: it looked 15-30% slower than it moved). Without the objects those
  // matches decide the pose again.
  if (with_outliers) RestoreOutliersOutside(excluded_instance, &f);
  if (OptimizePose(cam_, pose_opt_, &f) < settings_.tracking.min_inliers) return last_.T_c_w;
  return f.T_c_w;
}

bool Tracker::ReposeWithout(const std::vector<bool>& excluded_instance, bool tracked) {
  std::lock_guard<std::mutex> lock(map_->mutex);
  if (!tracked || lost_ || !last_.features) return false;
  Frame f = last_;
  int matched = 0;
  const int excluded = DropInstanceMatches(excluded_instance, &f, &matched);
  if (excluded == 0 || matched - excluded < settings_.tracking.min_inliers) return false;
  // The tracked pose's rejected static matches do not come back here (unlike LastPoseWithout):
  // this pose becomes the frame's, and with them back on standing_crowd's sparse checker floor the
  // track was 35-48 mm off at 14.15 s, where two standing people were judged dynamic with the
  // walker (precision 0.82 against 1.00).
  if (OptimizePose(cam_, pose_opt_, &f) < settings_.tracking.min_inliers) return false;
  f.ForgetOutliers();
  // Old camera to new camera, and a point's old world position to its new one.
  const Eigen::Isometry3d new_from_old = f.T_c_w * last_.T_c_w.inverse();
  const Eigen::Isometry3d move_point = f.T_c_w.inverse() * last_.T_c_w;
  if (have_velocity_) velocity_ = new_from_old * velocity_;
  last_good_T_c_w_ = f.T_c_w;
  if (pending_keyframe_ && last_keyframe_frame_ == frame_index_) {
    pending_keyframe_->T_c_w = f.T_c_w;
    for (size_t i = 0; i < f.size(); ++i) {
      MapPoint* p = pending_keyframe_->points[i];
      if (!new_point_[i] || !p || p->bad) continue;
      p->p_w = move_point * p->p_w;
      p->UpdateFromObservations();
    }
  }
  last_ = std::move(f);
  RecordFates();
  return true;
}

std::vector<Eigen::Vector3d> Tracker::LocalMapPointPositions() const {
  std::lock_guard<std::mutex> lock(map_->mutex);
  std::vector<Eigen::Vector3d> out;
  out.reserve(local_points_.size());
  for (const MapPoint* p : local_points_) {
    if (!p->bad) out.push_back(p->p_w);
  }
  return out;
}

TrackResult Tracker::Track(const StereoFrame& frame, std::shared_ptr<const FrameFeatures> features,
                           LocalMapper* mapper) {
  if (frame_index_ > 0 && frame.t_ns <= last_t_ns_) {
    throw InputError("frame timestamps must increase: " + std::to_string(frame.t_ns) + " ns after " +
                     std::to_string(last_t_ns_) + " ns");
  }
  TrackResult r;
  r.t_ns = frame.t_ns;
  r.external_prior = external_prior_;
  external_prior_ = false;  // a motion prior holds for one Track()
  // The first window of the motion-model search: sized from the external prior's error when
  // there is one and it has been measured (tracking.prior_window_*), motion_search_px otherwise.
  const TrackingSettings& ts = settings_.tracking;
  search_px_ = ts.motion_search_px;
  if (r.external_prior && !prior_miss_px_.empty() && median_depth_m_ > 0) {
    const double miss_px = *std::max_element(prior_miss_px_.begin(), prior_miss_px_.end());
    const double filter_px = cam_.fx * prior_sigma_m_ / median_depth_m_;
    search_px_ = std::clamp(ts.prior_window_factor * std::max(miss_px, filter_px), ts.prior_window_min_px,
                            3 * ts.motion_search_px);
  }
  r.search_px = search_px_;

  std::lock_guard<std::mutex> lock(map_->mutex);
  temporary_.clear();
  cur_ = Frame();
  cur_.t_ns = frame.t_ns;
  cur_.Reset(features);
  new_point_.assign(cur_.size(), 0);
  ++frame_index_;
  last_t_ns_ = frame.t_ns;

  // A lost tracker tries to relocalise first, however long the loss: a view of mapped ground ends
  // it in the map, where a new segment would carry the dead-reckoned pose's error from then on.
  bool relocalised = false;
  const bool was_lost = initialised_ && lost_;
  if (was_lost) {
    relocalised = Relocalise();
    if (relocalised) last_reloc_frame_ = frame_index_;
  }
  // A new segment after reinitialise_after_lost lost frames, or at once when the last lost frame
  // was carried by as many of its predecessor's points as a tracked frame needs (the view has
  // texture, only not the map's): waiting would chain frame-to-frame poses for nothing.
  const bool carried_well = last_carry_inliers_ >= settings_.tracking.min_inliers;
  const bool reinitialise = initialised_ && lost_ && !relocalised &&
                            (lost_frames_in_row_ >= settings_.tracking.reinitialise_after_lost || carried_well);
  last_carry_inliers_ = 0;
  if (!initialised_ || reinitialise) {
    // A new map segment continues from the last estimate: the frame carried from the last one's
    // points when it can be, else dead reckoning through the outage. Before the first map (the
    // camera dark from the start), an external motion prior (leg odometry + IMU) carries the
    // pose from the first frame's, so that the map starts where the robot has walked to.
    cur_.T_c_w = initialised_ ? (have_velocity_ ? velocity_ * last_.T_c_w : last_.T_c_w)
                              : (r.external_prior ? velocity_ * last_.T_c_w : Eigen::Isometry3d::Identity());
    if (reinitialise && !r.external_prior) {
      Eigen::Isometry3d carried;
      if (CarryFromLastFrame(cur_.T_c_w, &carried, &r.carry_inliers)) {
        velocity_ = carried * last_.T_c_w.inverse();
        have_velocity_ = true;
        cur_.T_c_w = carried;
      }
    }
    if (Initialise()) {
      r.status = TrackStatus::kInitialised;
      r.keyframe = true;
      // A first keyframe has nothing to triangulate with; a new segment's goes to mapping.
      if (reinitialise) pending_keyframe_ = map_->keyframes().back().get();
    } else {
      r.status = TrackStatus::kLost;
      if (initialised_) ++lost_frames_in_row_;
      // Too few stereo points for a segment: the next frame tries again (at once if this carry held).
      if (r.carry_inliers >= settings_.tracking.lost_carry_min_inliers) last_carry_inliers_ = r.carry_inliers;
    }
    r.T_w_c = cur_.T_c_w.inverse();
    last_ = cur_;
    last_outliers_.clear();
    RecordFates();
    return r;
  }

  bool ok = relocalised;  // a lost frame has had its one chance above
  const bool predicted = !lost_ && have_velocity_;
  const Eigen::Isometry3d predicted_T_c_w = velocity_ * last_.T_c_w;
  if (!lost_) {
    AddTemporaryPointsToLastFrame();
    if (have_velocity_) ok = TrackWithMotionModel(predicted_T_c_w);
    if (!ok) ok = TrackReferenceKeyFrame();
  }
  int inliers = 0, map_inliers = 0;
  if (ok) {
    inliers = TrackLocalMap(&map_inliers);
    const bool recently_relocalised = frame_index_ < last_reloc_frame_ + settings_.tracking.relocalised_frames;
    const int need = recently_relocalised ? std::max(settings_.tracking.min_inliers, settings_.tracking.relocalised_min_inliers)
                                          : settings_.tracking.min_inliers;
    // In the map only on map points: matches to the last frame's temporary points alone are
    // frame to frame (such a frame is lost and carried, not tracked).
    ok = map_inliers >= need;
  }
  r.inliers = inliers;
  r.map_inliers = map_inliers;
  if (ok) {
    r.status = lost_ ? TrackStatus::kRelocalised : TrackStatus::kTracking;
    if (r.status == TrackStatus::kTracking) {
      if (predicted) {
        const Eigen::Isometry3d miss = cur_.T_c_w * predicted_T_c_w.inverse();
        r.prior_err_deg = Eigen::AngleAxisd(miss.rotation()).angle() * 180.0 / M_PI;
        r.prior_err_mm = 1e3 * (cur_.T_c_w.inverse().translation() - predicted_T_c_w.inverse().translation()).norm();
      }
      if (predicted && r.external_prior) MeasurePriorMiss(predicted_T_c_w);
      velocity_ = cur_.T_c_w * last_.T_c_w.inverse();
      have_velocity_ = true;
    }
    lost_ = false;
    lost_frames_in_row_ = 0;
    last_good_T_c_w_ = cur_.T_c_w;
    DropTemporaryPoints(&cur_);
    if (NeedKeyFrame(inliers, mapper)) {
      KeyFrame* kf = CreateKeyFrame(mapper);
      r.keyframe = kf != nullptr;
    }
  } else {
    r.status = TrackStatus::kLost;
    lost_ = true;
    ++lost_frames_in_row_;
    // No pose from the map: carry the external motion prior, or else the last frame's own stereo
    // points (frame to frame) when enough of them hold, or else the constant velocity, so that the
    // trajectory has no gap.
    const Eigen::Isometry3d guess = have_velocity_ ? velocity_ * last_.T_c_w : last_.T_c_w;
    Eigen::Isometry3d carried = guess;
    if (!r.external_prior && CarryFromLastFrame(guess, &carried, &r.carry_inliers)) {
      velocity_ = carried * last_.T_c_w.inverse();
      have_velocity_ = true;
      // Only a frame that has also failed to relocalise counts towards a new segment: the first
      // lost frame after a tracked one is carried by points the map may still see.
      if (was_lost) last_carry_inliers_ = r.carry_inliers;
    }
    cur_.T_c_w = carried;
    DropTemporaryPoints(&cur_);
    cur_.ClearMatches();
  }
  // Outliers are forgotten before the frame becomes the last frame (kept aside for
  // LastPoseWithout).
  RememberOutliers(cur_);
  cur_.ForgetOutliers();
  r.T_w_c = cur_.T_c_w.inverse();
  last_ = cur_;
  RecordFates();
  return r;
}

void Tracker::RecordFates() {
  last_fates_.assign(last_.size(), 0);
  for (size_t i = 0; i < last_.size(); ++i) {
    const MapPoint* p = last_.points[i];
    if (new_point_[i]) {
      last_fates_[i] = 2;
    } else if (p && !p->bad && p->id >= 0 && !last_.outlier[i]) {
      last_fates_[i] = 1;
    }
  }
}

bool Tracker::Initialise() {
  const FrameFeatures& f = *cur_.features;
  int with_depth = 0;
  for (float d : f.depth) with_depth += d > 0 ? 1 : 0;
  if (with_depth < settings_.tracking.init_min_points) return false;
  KeyFrame* kf = map_->AddKeyFrame(cur_);
  // The first keyframe of every map segment (the first map, or a new one after a long loss) is
  // held fixed in bundle adjustment: it anchors the segment's gauge.
  kf->fixed = true;
  last_good_T_c_w_ = cur_.T_c_w;
  const Eigen::Isometry3d T_w_c = cur_.T_c_w.inverse();
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] <= 0) continue;
    MapPoint* p = map_->AddPoint(T_w_c * f.Unproject(cam_, static_cast<int>(i)), kf);
    p->object = f.object[i];
    Map::AddObservation(p, kf, static_cast<int>(i));
    p->UpdateFromObservations();
    cur_.points[i] = p;
    new_point_[i] = 1;
  }
  initialised_ = true;
  lost_ = false;
  lost_frames_in_row_ = 0;
  have_velocity_ = false;
  reference_ = kf;
  last_keyframe_frame_ = frame_index_;
  local_keyframes_ = {kf};
  return true;
}

void Tracker::AddTemporaryPointsToLastFrame() {
  // As ORB-SLAM does for stereo: the last frame's close stereo features without a map point get
  // temporary points, so that the motion-model search has enough to match.
  const FrameFeatures& f = *last_.features;
  std::vector<std::pair<float, int>> by_depth;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] > 0) by_depth.emplace_back(f.depth[i], static_cast<int>(i));
  }
  std::sort(by_depth.begin(), by_depth.end());
  const Eigen::Isometry3d T_w_c = last_.T_c_w.inverse();
  int added = 0;
  for (const auto& [d, i] : by_depth) {
    if (last_.points[i] && !last_.points[i]->bad) {
      if (d > cam_.close_depth_m && added > settings_.tracking.keyframe_new_points) break;
      continue;
    }
    auto p = std::make_unique<MapPoint>(-1, T_w_c * f.Unproject(cam_, i), nullptr);
    p->SetDescriptor(f.descriptors, i);
    last_.points[i] = p.get();
    last_.outlier[i] = false;
    temporary_.push_back(std::move(p));
    ++added;
    if (d > cam_.close_depth_m && added > settings_.tracking.keyframe_new_points) break;
  }
}

void Tracker::DropTemporaryPoints(Frame* f) const {
  for (auto& p : f->points) {
    if (p && p->id < 0) p = nullptr;
  }
}

void Tracker::MeasurePriorMiss(const Eigen::Isometry3d& predicted_T_c_w) {
  // Over the inliers of the frame just tracked: their depth, and how far the prediction put them
  // from where the tracked pose does (px).
  std::vector<double> depth, miss;
  for (size_t i = 0; i < cur_.size(); ++i) {
    const MapPoint* p = cur_.points[i];
    if (!p || cur_.outlier[i]) continue;
    const Eigen::Vector3d tracked = cur_.T_c_w * p->p_w;
    const Eigen::Vector3d guessed = predicted_T_c_w * p->p_w;
    if (tracked.z() <= 0 || guessed.z() <= 0) continue;
    depth.push_back(tracked.z());
    miss.push_back((cam_.Project(tracked) - cam_.Project(guessed)).norm());
  }
  if (depth.empty()) return;
  std::nth_element(depth.begin(), depth.begin() + depth.size() / 2, depth.end());
  median_depth_m_ = depth[depth.size() / 2];
  const size_t k = std::min(miss.size() - 1, static_cast<size_t>(0.9 * miss.size()));
  std::nth_element(miss.begin(), miss.begin() + k, miss.end());
  prior_miss_px_.push_back(miss[k]);
  while (static_cast<int>(prior_miss_px_.size()) > settings_.tracking.prior_window_frames) prior_miss_px_.pop_front();
}

bool Tracker::TrackWithMotionModel(const Eigen::Isometry3d& predicted) {
  // The prediction (constant velocity, or the external prior) with the first window (search_px_);
  // when that matches weakly, a window three times as wide, the last pose (no motion) with five
  // times the window, and the reference keyframe by descriptor; the attempt with the most
  // inliers wins. A trotting robot's camera
  // turns 4 degrees a frame and, on a jolt, 10 (60 px here): the prediction can miss by more
  // than the normal window.
  const double radius = search_px_;
  const int good = static_cast<int>(settings_.tracking.weak_inliers_factor * settings_.tracking.min_inliers);
  const std::pair<Eigen::Isometry3d, double> attempts[] = {
      {predicted, radius}, {predicted, 3 * radius}, {last_.T_c_w, 5 * radius}};
  int best = -1;
  Frame best_frame;
  auto keep_if_best = [&](int inliers) {
    cur_.ForgetOutliers();
    if (inliers > best) {
      best = inliers;
      best_frame = cur_;
    }
  };
  for (const auto& [pose, r] : attempts) {
    cur_.T_c_w = pose;
    cur_.ClearMatches();
    if (matcher_->SearchByProjection(last_, r, &cur_) < settings_.tracking.min_inliers_motion) continue;
    keep_if_best(OptimizePose(cam_, pose_opt_, &cur_));
    if (best >= good) break;
  }
  if (best < good && TrackReferenceKeyFrame()) keep_if_best(cur_.MatchedCount());
  if (best < 0) return false;
  cur_ = best_frame;
  return best >= settings_.tracking.min_inliers_motion;
}

bool Tracker::CarryFromLastFrame(const Eigen::Isometry3d guess, Eigen::Isometry3d* pose, int* inliers) {
  *inliers = 0;
  const int need = settings_.tracking.lost_carry_min_inliers;
  if (need <= 0 || !last_.features) return false;
  // The last frame's stereo features as points where its (tracked or carried) pose puts them.
  // Frames tracked from the map have theirs already; a lost frame has none.
  if (temporary_.empty()) AddTemporaryPointsToLastFrame();
  const double radius = search_px_;
  const std::pair<Eigen::Isometry3d, double> attempts[] = {{guess, radius}, {guess, 3 * radius}, {last_.T_c_w, 5 * radius}};
  int best = -1;
  Eigen::Isometry3d best_pose = guess;
  for (const auto& [start, r] : attempts) {
    cur_.T_c_w = start;
    cur_.ClearMatches();
    if (matcher_->SearchByProjection(last_, r, &cur_) < need) continue;
    const int n = OptimizePose(cam_, pose_opt_, &cur_);
    if (n > best) {
      best = n;
      best_pose = cur_.T_c_w;
    }
    if (best >= settings_.tracking.weak_inliers_factor * settings_.tracking.min_inliers) break;
  }
  cur_.ClearMatches();
  cur_.T_c_w = guess;
  *inliers = std::max(best, 0);
  if (best < need) return false;
  *pose = best_pose;
  return true;
}

void Tracker::Pinned(std::vector<const KeyFrame*>* keyframes, std::vector<const MapPoint*>* points) const {
  keyframes->push_back(reference_);
  keyframes->push_back(pending_keyframe_);
  keyframes->insert(keyframes->end(), local_keyframes_.begin(), local_keyframes_.end());
  points->insert(points->end(), local_points_.begin(), local_points_.end());
  for (const Frame* f : {&cur_, &last_}) points->insert(points->end(), f->points.begin(), f->points.end());
  points->insert(points->end(), last_outliers_.begin(), last_outliers_.end());
}

bool Tracker::TrackReferenceKeyFrame() {
  if (!reference_ || reference_->bad) {
    for (auto it = map_->keyframes().rbegin(); it != map_->keyframes().rend(); ++it) {
      if (!(*it)->bad) {
        reference_ = it->get();
        break;
      }
    }
  }
  cur_.ClearMatches();
  const int n = matcher_->SearchByDescriptor(*reference_, &cur_);
  if (n < kMinDescriptorMatches) return false;
  cur_.T_c_w = last_.T_c_w;
  const int inliers = OptimizePose(cam_, pose_opt_, &cur_);
  cur_.ForgetOutliers();
  return inliers >= kMinPoseInliers;
}

void Tracker::AddSpatialKeyFrames(std::vector<KeyFrame*>* local, std::set<KeyFrame*>* in_local) const {
  const TrackingSettings& ts = settings_.tracking;
  if (ts.spatial_keyframes <= 0) return;
  const std::vector<KeyFrame*> near =
      map_->NearbyKeyFrames(cur_.T_c_w.inverse(), ts.spatial_radius_m, ts.spatial_max_angle_deg, *in_local,
                            static_cast<size_t>(ts.spatial_keyframes));
  for (KeyFrame* k : near) {
    in_local->insert(k);
    local->push_back(k);
  }
}

int Tracker::TrackLocalMap(int* map_inliers) {
  // Local keyframes: those that see the frame's points, then their best neighbours.
  KeyFrameMap<int> counter;
  for (size_t i = 0; i < cur_.size(); ++i) {
    MapPoint* p = cur_.points[i];
    if (!p || p->bad || p->id < 0) continue;
    for (const auto& [kf, idx] : p->observations) {
      if (!kf->bad) ++counter[kf];
    }
  }
  std::vector<std::pair<int, KeyFrame*>> ranked;
  for (const auto& [kf, n] : counter) ranked.emplace_back(n, kf);
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->id > b.second->id;
  });
  const size_t max_kfs = static_cast<size_t>(settings_.tracking.local_keyframes);
  std::vector<KeyFrame*> local;
  std::set<KeyFrame*> in_local;
  for (const auto& [n, kf] : ranked) {
    if (local.size() >= max_kfs) break;
    if (in_local.insert(kf).second) local.push_back(kf);
  }
  if (!ranked.empty()) reference_ = ranked.front().second;
  const size_t direct = local.size();
  for (size_t i = 0; i < direct && local.size() < max_kfs; ++i) {
    for (KeyFrame* n : local[i]->BestCovisible(5)) {
      if (local.size() >= max_kfs) break;
      if (in_local.insert(n).second) local.push_back(n);
    }
  }
  if (local.empty() && reference_ && !reference_->bad) local.push_back(reference_);
  AddSpatialKeyFrames(&local, &in_local);
  local_keyframes_ = local;

  local_points_.clear();
  for (KeyFrame* kf : local) {
    for (MapPoint* p : kf->points) {
      if (p && p->Matchable() && p->local_map_frame != frame_index_) {
        p->local_map_frame = frame_index_;
        local_points_.push_back(p);
      }
    }
  }
  for (size_t i = 0; i < cur_.size(); ++i) {
    if (cur_.points[i] && !cur_.points[i]->bad) ++cur_.points[i]->visible;
  }
  matcher_->SearchLocalPoints(local_points_, settings_.tracking.local_map_search_px, &cur_, true);
  int inliers = OptimizePose(cam_, pose_opt_, &cur_);
  if (inliers < settings_.tracking.weak_inliers_factor * settings_.tracking.min_inliers) {
    // Few matches usually mean a poor prediction (a jolt of the trunk): search again from the
    // optimised pose with a window three times as wide.
    cur_.ForgetOutliers();
    matcher_->SearchLocalPoints(local_points_, 3 * settings_.tracking.local_map_search_px, &cur_, false);
    inliers = OptimizePose(cam_, pose_opt_, &cur_);
  }
  *map_inliers = 0;
  for (size_t i = 0; i < cur_.size(); ++i) {
    MapPoint* p = cur_.points[i];
    if (!p || cur_.outlier[i] || p->bad) continue;
    ++p->found;
    // The last frame's temporary points (id -1) help the pose but are not the map.
    if (p->id >= 0) ++*map_inliers;
  }
  return inliers;
}

bool Tracker::Relocalise() {
  // Candidates: the most recent keyframes and those nearest the last tracked position (not the
  // pose dead-reckoned since, which drifts with every lost frame).
  std::vector<KeyFrame*> good;
  for (const auto& kf : map_->keyframes()) {
    if (!kf->bad) good.push_back(kf.get());
  }
  std::vector<KeyFrame*> cands;
  std::set<KeyFrame*> chosen;
  for (auto it = good.rbegin(); it != good.rend() && cands.size() < kRelocRecentKeyframes; ++it) {
    if (chosen.insert(*it).second) cands.push_back(*it);
  }
  if (cands.size() < kRelocCandidates) {
    // Any distance, any viewing direction.
    const std::vector<KeyFrame*> near = map_->NearbyKeyFrames(
        last_good_T_c_w_.inverse(), std::numeric_limits<double>::infinity(), 180, chosen, kRelocCandidates - cands.size());
    cands.insert(cands.end(), near.begin(), near.end());
  }
  for (KeyFrame* kf : cands) {
    cur_.ClearMatches();
    const int n = matcher_->SearchByDescriptor(*kf, &cur_);
    if (n < kMinDescriptorMatches) continue;
    std::vector<cv::Point3f> obj;
    std::vector<cv::Point2f> img;
    std::vector<int> idx;
    for (size_t i = 0; i < cur_.size(); ++i) {
      if (!cur_.points[i]) continue;
      const Eigen::Vector3d& p = cur_.points[i]->p_w;
      obj.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
      img.push_back(cur_.features->keypoints[i].pt);
      idx.push_back(static_cast<int>(i));
    }
    const cv::Matx33d K(cam_.fx, 0, cam_.cx, 0, cam_.fy, cam_.cy, 0, 0, 1);
    cv::Mat rvec, tvec;
    std::vector<int> inl;
    // Deterministic without seeding: OpenCV's RANSAC draws from a generator of its own with a
    // fixed seed (cv::setRNGSeed does not reach it; test_slam_system checks the determinism).
    if (!cv::solvePnPRansac(obj, img, K, cv::noArray(), rvec, tvec, false, kRelocRansacIterations, kRelocRansacPx,
                            kRelocRansacConfidence, inl, cv::SOLVEPNP_EPNP) ||
        static_cast<int>(inl.size()) < settings_.tracking.relocalise_ransac_min_inliers) {
      continue;
    }
    cv::Mat R;
    cv::Rodrigues(rvec, R);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) T.linear()(a, b) = R.at<double>(a, b);
      T.translation()(a) = tvec.at<double>(a);
    }
    std::vector<bool> keep(cur_.size(), false);
    for (int k : inl) keep[idx[k]] = true;
    for (size_t i = 0; i < cur_.size(); ++i) {
      if (!keep[i]) cur_.points[i] = nullptr;
    }
    cur_.T_c_w = T;
    int inliers = OptimizePose(cam_, pose_opt_, &cur_);
    if (inliers < kMinPoseInliers) continue;
    // More matches from the candidate's neighbourhood, then the pose again.
    std::vector<MapPoint*> pts;
    std::set<MapPoint*> seen;
    std::vector<KeyFrame*> hood = kf->BestCovisible(kRelocNeighbours);
    hood.push_back(kf);
    for (KeyFrame* h : hood) {
      for (MapPoint* p : h->points) {
        if (p && !p->bad && seen.insert(p).second) pts.push_back(p);
      }
    }
    cur_.ForgetOutliers();
    matcher_->SearchLocalPoints(pts, kRelocSearchPx, &cur_, false);
    inliers = OptimizePose(cam_, pose_opt_, &cur_);
    if (inliers >= settings_.tracking.relocalise_min_inliers) {
      reference_ = kf;
      // The next frame is predicted at this pose (no motion) and searched with the wide window.
      velocity_ = Eigen::Isometry3d::Identity();
      have_velocity_ = true;
      cur_.ForgetOutliers();
      return true;
    }
  }
  cur_.ClearMatches();
  return false;
}

bool Tracker::NeedKeyFrame(int inliers, LocalMapper* mapper) const {
  const int64_t since = frame_index_ - last_keyframe_frame_;
  if (since < settings_.tracking.keyframe_min_frames) return false;
  // A weakly tracked frame would put its doubtful pose into the map.
  if (inliers < settings_.tracking.keyframe_min_inliers) return false;
  if (frame_index_ < last_reloc_frame_ + settings_.tracking.relocalised_frames && map_->GoodKeyFrames() > kRelocNoKeyframeMapSize) {
    return false;
  }
  const int min_obs = map_->GoodKeyFrames() <= 2 ? 2 : 3;
  const int ref_matches = reference_ ? reference_->TrackedPoints(min_obs) : 0;
  const FrameFeatures& f = *cur_.features;
  int tracked_close = 0, untracked_close = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] <= 0 || f.depth[i] > cam_.close_depth_m) continue;
    if (cur_.points[i] && !cur_.outlier[i]) {
      ++tracked_close;
    } else {
      ++untracked_close;
    }
  }
  const bool need_close = tracked_close < settings_.tracking.close_tracked_max && untracked_close > settings_.tracking.close_points_min;
  const bool mapper_idle = !mapper || mapper->Queued() == 0;
  const bool c1a = since >= settings_.tracking.keyframe_max_frames;
  const bool c1b = mapper_idle;
  const bool c1c = inliers < kKeyframeLowShare * ref_matches || need_close;
  const bool c2 = (inliers < settings_.tracking.keyframe_ratio * ref_matches || need_close) && inliers > kKeyframeMinFloor;
  if (!((c1a || c1b || c1c) && c2)) return false;
  // Real-time mode: when mapping is behind, only a keyframe that is really needed is queued.
  return mapper_idle || (mapper && mapper->Queued() < 3);
}

KeyFrame* Tracker::CreateKeyFrame(LocalMapper* mapper) {
  KeyFrame* kf = map_->AddKeyFrame(cur_);
  reference_ = kf;
  last_keyframe_frame_ = frame_index_;
  // New map points from the nearest stereo features that have none: all the close ones, and at
  // least the nearest tracking.keyframe_new_points.
  const FrameFeatures& f = *kf->features;
  std::vector<std::pair<float, int>> by_depth;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] > 0) by_depth.emplace_back(f.depth[i], static_cast<int>(i));
  }
  std::sort(by_depth.begin(), by_depth.end());
  const Eigen::Isometry3d T_w_c = kf->T_c_w.inverse();
  std::vector<MapPoint*> created;
  int considered = 0;
  for (const auto& [d, i] : by_depth) {
    if (d > cam_.close_depth_m && considered > settings_.tracking.keyframe_new_points) break;
    ++considered;
    if (kf->points[i]) continue;
    MapPoint* p = map_->AddPoint(T_w_c * f.Unproject(cam_, i), kf);
    p->object = f.object[i];
    Map::AddObservation(p, kf, i);
    p->UpdateFromObservations();
    cur_.points[i] = p;
    new_point_[i] = 1;
    created.push_back(p);
  }
  if (mapper) mapper->AddRecentPoints(created);
  pending_keyframe_ = kf;
  return kf;
}

}  // namespace viqu::slam

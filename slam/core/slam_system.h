#pragma once
// The stereo (or RGB-D) visual SLAM system: feed it frames in time order, get a pose and a
// tracking status for every frame. Mapping runs inline after each keyframe (mapping.mode: sync,
// deterministic) or on a second thread (realtime). Heavy headers (Ceres) stay out of this one.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "slam/core/dynamic_objects.h"
#include "slam/measurements/stereo_frame.h"
#include "slam/settings/slam_settings.h"

namespace viqu::slam {

enum class TrackStatus {
  kInitialised,  // first frame: the map was created from its stereo points; pose is the origin
  kTracking,     // tracked against the map
  kRelocalised,  // was lost; found again by matching against keyframes
  kLost,         // no pose from vision: the pose is the motion-model prediction
};
const char* TrackStatusName(TrackStatus s);

// What became of one feature of a frame (TrackResult::marks, for overlays).
enum class FeatureFate : uint8_t {
  kUnmatched,  // no map point (or an outlier)
  kTracked,    // an inlier of a map point
  kNew,        // a new map point was made from it (keyframes)
  kDropped,    // on an object judged dynamic: removed before tracking
};
struct FeatureMark {
  float x = 0, y = 0;  // left image (px)
  FeatureFate fate = FeatureFate::kUnmatched;
};

struct TrackResult {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();  // left camera in the SLAM world
  TrackStatus status = TrackStatus::kLost;
  bool keyframe = false;         // this frame became a keyframe
  int features = 0;              // features extracted in the left image
  int features_dropped = 0;      // of those, removed on dynamic objects before tracking, or from the
                                 // frame's pose after it for objects judged dynamic on this frame
  int stereo_points = 0;         // features with depth
  int inliers = 0;               // matches kept by pose optimisation (map points and the last frame's temporary ones)
  int map_inliers = 0;           // of those, map points: a frame with fewer than tracking.min_inliers is lost
  int carry_inliers = 0;         // a lost frame carried without an external prior: inliers among the last frame's
                                 // stereo points (its pose came from them when >= tracking.lost_carry_min_inliers)
  double track_ms = 0;           // wall time of Track() (ms), the dynamic stage included
  double dynamic_ms = 0;         // of that, the dynamic-object stage (ms)
  double excluded_share = 0;     // share of inliers on movable objects (judged with a pose without them above
                                 // dynamic.adaptive.static_pose_min_share)
  // How far the tracker's prediction of this frame's pose (the motion prior of SetMotionPrior, or
  // the constant-velocity guess) was from the pose tracked: rotation (deg) and camera centre
  // (mm). Negative when there was no prediction or the frame was not tracked from the last one.
  double prior_err_deg = -1;
  double prior_err_mm = -1;
  bool external_prior = false;   // the prediction came from SetMotionPrior
  double search_px = 0;          // the first window of the search from the prediction (px, level 0)
  std::vector<ObjectReport> objects;  // movable objects in the frame's masks
  std::vector<FeatureMark> marks;     // every feature's fate; only with SetRecordFeatures(true)
};

struct SlamStats {
  int frames = 0;
  int lost_frames = 0;
  int relocalisations = 0;
  int keyframes = 0;             // keyframes in the map now
  int map_points = 0;            // map points in the map now
  std::vector<double> track_ms;  // per frame (ms)
  std::vector<double> local_ba_ms;  // per local BA (ms)
  std::vector<double> dynamic_ms;   // per frame (ms)
  int object_points_erased = 0;     // map points culled because their object turned dynamic
  int object_points_retired = 0;    // map points of such objects kept for BA with their earlier
                                    // observations (dynamic.keep_past_observations), never matched again
  int64_t keyframes_freed = 0;      // culled keyframes freed (Map::Reclaim)
  int64_t map_points_freed = 0;     // culled map points freed
  int64_t keyframes_held = 0;       // keyframes allocated now (good, and culled but still held)
  int64_t map_points_held = 0;      // map points allocated now
  size_t map_heap_bytes = 0;        // Map::HeapBytes(): what the map's objects hold now
};

class SlamSystem {
 public:
  // `world_from_first_camera` places the map: the first frame's camera pose in the output world
  // frame (identity: the trajectory starts at the origin).
  explicit SlamSystem(const SlamSettings& settings,
                      const Eigen::Isometry3d& world_from_first_camera = Eigen::Isometry3d::Identity());
  ~SlamSystem();
  SlamSystem(const SlamSystem&) = delete;
  SlamSystem& operator=(const SlamSystem&) = delete;

  // Tracks one frame. Frames must come in increasing time (InputError otherwise). Stereo input
  // uses left_rgb + right_rgb; rgbd input uses left_rgb + left_depth_m.
  TrackResult Track(const StereoFrame& frame);

  // A motion prior for the next Track(): the camera's motion since the last tracked frame,
  // T_cur_last (for example from leg odometry and the IMU, slam.mode full). It replaces the
  // constant-velocity guess in tracking and carries the pose while vision fails (lost frames,
  // a new map segment after loss starts from it). Used for one frame. sigma_m: the standard
  // deviation of its translation (m; 0 = unknown), which can widen the first search window
  // (tracking.prior_window_*).
  void SetMotionPrior(const Eigen::Isometry3d& T_cur_last, double sigma_m = 0);

  // Fill TrackResult::marks (for overlay videos; off by default).
  void SetRecordFeatures(bool on);

  // Waits for the mapping thread (realtime mode) to finish its queue.
  void Finish();

  SlamStats Stats() const;

  // The keyframes in the map now (culled ones left out), in creation order: for tests, reports
  // and viewers.
  struct KeyFrameInfo {
    int64_t t_ns = 0;
    Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();  // in the output world frame
    bool fixed = false;  // held constant in bundle adjustment (the first keyframe of each map segment)
  };
  std::vector<KeyFrameInfo> KeyFrames() const;

  // The map points in the map now (culled ones left out), in the output world frame: for viewers.
  struct MapPointInfo {
    Eigen::Vector3d p_w = Eigen::Vector3d::Zero();  // (m)
    uint16_t object = 0;  // segmentation instance of the feature that created it (0 = none)
  };
  std::vector<MapPointInfo> MapPoints() const;
  const SlamSettings& settings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace viqu::slam

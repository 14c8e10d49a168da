#pragma once
// Tracking: features of each frame, its pose against the map (constant-velocity motion model,
// reference keyframe as fallback, then the local map), outlier rejection, the keyframe
// decision, and relocalisation when lost.
#include <deque>
#include <memory>
#include <set>
#include <vector>

#include <Eigen/Geometry>

#include "slam/core/camera.h"
#include "slam/core/frame.h"
#include "slam/core/matcher.h"
#include "slam/core/pose_optimizer.h"
#include "slam/core/slam_system.h"
#include "slam/features/orb_extractor.h"
#include "slam/features/stereo_matcher.h"

namespace viqu::slam {

class KeyFrame;
class LocalMapper;
class Map;
class MapPoint;

class Tracker {
 public:
  Tracker(const SlamSettings& settings, Map* map);
  ~Tracker();

  // Tracks one frame under the map mutex. The camera model is fixed by SetCamera() from the
  // first frame; later frames must have the same intrinsics. `mapper` (may be null) is asked whether it is idle
  // and is told about new stereo points; a new keyframe is handed over by TakePendingKeyFrame()
  // after Track() returns, outside the lock.
  // `features` are the frame's features as ExtractFeatures() gave them, less those the
  // dynamic-object stage removed.
  TrackResult Track(const StereoFrame& frame, std::shared_ptr<const FrameFeatures> features, LocalMapper* mapper);

  // Features of both images, stereo depth, and the segmentation instance under each feature.
  // InputError for an instance image of another size than the image.
  std::shared_ptr<FrameFeatures> ExtractFeatures(const StereoFrame& frame) const;

  // The pose of the frame just tracked (map to camera) optimised again without the matches on
  // features whose instance `excluded` says, and (`with_outliers`) with the other matches the
  // tracked pose had rejected as outliers (a large moving object drags the tracked pose along and
  // makes much of the static scene look wrong to it); the tracked pose when fewer than
  // tracking.min_inliers remain or when the excluded share of the frame's inliers is below
  // `min_share` (then nothing is optimised). `*excluded_share` (may be null): that share.
  Eigen::Isometry3d LastPoseWithout(const std::vector<bool>& excluded_instance, double min_share,
                                    bool with_outliers,
                                    double* excluded_share);
  // The frame just tracked loses its matches on features whose instance `excluded_instance` says
  // (objects judged dynamic after it was tracked) and its pose is optimised again without them;
  // the motion model, and a keyframe made from the frame with the map points it created, move
  // with it. Only after a frame tracked normally (not lost, relocalised or initialised: `tracked`)
  // and when at least tracking.min_inliers remain; otherwise nothing changes. True when it moved.
  bool ReposeWithout(const std::vector<bool>& excluded_instance, bool tracked);
  // The pose of the frame just tracked (map to camera).
  Eigen::Isometry3d LastPose() const { return last_.T_c_w; }
  // Per feature of the last Track()'s `features`: 0 unmatched (or an outlier), 1 tracked (an
  // inlier of a map point), 2 a map point made from it in this frame (a new keyframe's).
  const std::vector<uint8_t>& LastFeatureFates() const { return last_fates_; }
  // Positions of the local map's good points (map frame, m) after the last Track().
  std::vector<Eigen::Vector3d> LocalMapPointPositions() const;
  // Every keyframe and map point the tracker holds between frames (reference, pending keyframe,
  // local map, the last and current frames' matches): Map::Reclaim must keep them.
  void Pinned(std::vector<const KeyFrame*>* keyframes, std::vector<const MapPoint*>* points) const;
  KeyFrame* TakePendingKeyFrame() {
    KeyFrame* kf = pending_keyframe_;
    pending_keyframe_ = nullptr;
    return kf;
  }

  // Motion of the camera from the last frame to the next one (T_cur_last), used instead of the
  // constant-velocity model for the next Track() only (SlamSystem::SetMotionPrior); sigma_m: the
  // standard deviation of its translation (m), which widens the first search window.
  void SetMotionPrior(const Eigen::Isometry3d& T_cur_last, double sigma_m) {
    velocity_ = T_cur_last;
    have_velocity_ = true;
    external_prior_ = true;
    prior_sigma_m_ = sigma_m;
  }

  bool HasCamera() const { return have_camera_; }
  const StereoCamera& camera() const { return cam_; }
  void SetCamera(const StereoFrame& frame);

 private:
  void RecordFates();  // fills last_fates_ from last_ at the end of Track()
  // Removes from `f` its matches (to good map points) on features whose instance
  // `excluded_instance` says; returns how many, and in `*matched` how many good matches it had.
  int DropInstanceMatches(const std::vector<bool>& excluded_instance, Frame* f, int* matched) const;
  // Gives `f` (the last frame) back the matches its tracked pose judged outliers, except on the
  // excluded instances (see LastPoseWithout); returns how many.
  int RestoreOutliersOutside(const std::vector<bool>& excluded_instance, Frame* f) const;
  void RememberOutliers(const Frame& f);
  bool Initialise();
  void AddTemporaryPointsToLastFrame();
  bool TrackWithMotionModel(const Eigen::Isometry3d& predicted);  // predicted: T_c_w from velocity_
  // After a frame tracked from an external prior: the median depth of its inliers and the 90th
  // percentile of the prior's miss in pixels (prior_miss_px_).
  void MeasurePriorMiss(const Eigen::Isometry3d& predicted_T_c_w);
  bool TrackReferenceKeyFrame();
  // A lost frame's pose from the last frame's stereo points alone (its map points and temporary
  // ones), searched from `guess` as the motion model does: true, with the pose, when at least
  // tracking.lost_carry_min_inliers are inliers; `inliers`: the best count found. `guess` by value:
  // callers pass cur_.T_c_w, which the search moves (and puts back to the guess).
  bool CarryFromLastFrame(Eigen::Isometry3d guess, Eigen::Isometry3d* pose, int* inliers);
  // Tracks the local map; returns the pose's inliers, of which `map_inliers` are map points (the
  // rest the last frame's temporary stereo points).
  int TrackLocalMap(int* map_inliers);
  // Appends to the local keyframes up to tracking.spatial_keyframes others near the predicted
  // camera (centre within spatial_radius_m, optical axis within spatial_max_angle_deg), nearest first.
  void AddSpatialKeyFrames(std::vector<KeyFrame*>* local, std::set<KeyFrame*>* in_local) const;
  bool Relocalise();
  bool NeedKeyFrame(int inliers, LocalMapper* mapper) const;
  KeyFrame* CreateKeyFrame(LocalMapper* mapper);
  void DropTemporaryPoints(Frame* f) const;

  SlamSettings settings_;
  Map* map_;
  OrbExtractor extractor_;
  OrbExtractor right_extractor_;   // its own instance: the right image is extracted on another thread
  StereoMatcher stereo_;
  StereoCamera cam_;
  bool have_camera_ = false;
  std::unique_ptr<Matcher> matcher_;
  PoseOptimizerOptions pose_opt_;

  Frame cur_, last_;
  bool initialised_ = false;
  bool lost_ = false;
  int lost_frames_in_row_ = 0;
  int last_carry_inliers_ = 0;  // inliers of the last frame's carry from its predecessor (0: not carried)
  Eigen::Isometry3d velocity_ = Eigen::Isometry3d::Identity();  // T_cur_last of the last step
  Eigen::Isometry3d last_good_T_c_w_ = Eigen::Isometry3d::Identity();  // last pose tracked by vision
  bool have_velocity_ = false;
  std::vector<MapPoint*> last_outliers_;  // per feature of the last frame: the map point it matched when the
                                          // tracked pose judged that match an outlier (else null)
  bool external_prior_ = false;  // velocity_ was set by SetMotionPrior for this Track()
  double prior_sigma_m_ = 0;     // its translation's standard deviation (m)
  // The first search window for this frame (px, level 0), and what sizes it with an external
  // prior: the prior's recent misses (each frame's 90th percentile, px) and the median depth of
  // the last frame tracked from one (m).
  double search_px_ = 0;
  std::deque<double> prior_miss_px_;
  double median_depth_m_ = 0;
  KeyFrame* reference_ = nullptr;
  KeyFrame* pending_keyframe_ = nullptr;
  int64_t frame_index_ = 0, last_keyframe_frame_ = 0, last_reloc_frame_ = -1000;
  int64_t last_t_ns_ = 0;
  std::vector<std::unique_ptr<MapPoint>> temporary_;  // visual-odometry points of the last frame
  std::vector<KeyFrame*> local_keyframes_;
  std::vector<MapPoint*> local_points_;
  std::vector<uint8_t> new_point_;   // per feature of the current frame: a map point was made from it
  std::vector<uint8_t> last_fates_;  // LastFeatureFates()
};

}  // namespace viqu::slam

#pragma once
// Fusion of the visual estimate with leg odometry + IMU (slam.mode full). Per camera frame:
//  - before tracking, the camera's motion from the tracker's last pose to the filter's becomes the
//    tracker's motion prior (instead of the constant-velocity guess), with the uncertainty of its
//    translation (the filter's velocity covariance over the interval), which sizes the tracker's
//    first search window together with the prior's measured misses; while vision fails it
//    carries the pose, and a new map segment after a loss starts from it;
//  - after tracking, a frame tracked with enough inliers corrects the filter: its position and
//    orientation are set to the visual ones (vision is about ten times more accurate here), the
//    orientation levelled to the IMU's mean force if it tilts beyond lo.fusion_tilt_gate_deg
//    from it (a tracker on few points before a loss); a frame that does not correct it has the
//    filter's own orientation checked the same way. The tracker's next prediction is then the
//    filter's pose, so a new map segment after a loss starts level.
// The filter keeps running on every IMU and encoder sample in between.
#include <optional>

#include <Eigen/Geometry>

#include "slam/core/slam_system.h"
#include "slam/lo/leg_odometry.h"

namespace viqu::slam {

class VisualLegFusion {
 public:
  // `lo` must be started (anchored at the same world pose as the map); T_body_cam: the left
  // camera's optical frame in the trunk (IMU) frame.
  VisualLegFusion(lo::LegOdometry* lo, const Eigen::Isometry3d& T_body_cam, int min_inliers)
      : lo_(lo), T_body_cam_(T_body_cam), min_inliers_(min_inliers) {}

  // Gives `system` the motion from the camera pose it gave the last frame to the filter's camera
  // pose now (nothing before the first), so that its prediction is the filter's pose.
  void BeforeTrack(SlamSystem* system);
  // That prior (what BeforeTrack gives): T_cur_last and its translation's standard deviation (m).
  struct Prior {
    Eigen::Isometry3d T_cur_last;
    double sigma_m = 0;
  };
  std::optional<Prior> NextPrior();
  // Corrects the filter with the frame's visual pose when it was tracked well.
  void AfterTrack(const TrackResult& r);

  int corrections() const { return corrections_; }
  int frames_carried() const { return carried_; }  // frames without a visual correction
  int levellings() const { return lo_->levellings(); }  // orientations levelled by the tilt gate
  int bias_updates() const { return lo_->vision_bias_updates(); }  // gyro bias corrections from vision
  Eigen::Vector3d gyro_bias() const { return lo_->attitude().gyro_bias(); }  // the fused filter's (rad/s, body)

 private:
  lo::LegOdometry* lo_;
  Eigen::Isometry3d T_body_cam_;
  int min_inliers_;
  // The camera pose the tracker gave the last frame (the filter's before the first AfterTrack).
  std::optional<Eigen::Isometry3d> last_T_w_c_;
  int64_t last_t_ns_ = 0;                        // the filter's time then (ns)
  int corrections_ = 0, carried_ = 0;
};

}  // namespace viqu::slam

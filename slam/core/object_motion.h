#pragma once
// The `adaptive` dynamic test (a well-posed variant of the paper's eqs. 2-4): does an object move
// in the world? Each frame, the object's features with stereo depth are put in the world frame
// (with a pose from features outside the movable objects when those carry much of the view) and
// matched by descriptor with the object's features of about `lag_s` earlier. The component-wise
// median of the matched points' world displacements is the object's motion; it is compared with
// `threshold_m` plus `k_sigma` standard errors of that median, from stereo depth noise
// (sigma_z = z^2 * disparity_sigma / bf per point). Unlike the norm of world positions, this sees
// tangential motion; unlike mask depth, it does not change with the robot's own motion; and unlike
// the mean of whatever points are visible, it compares the same points, so an object sliding out of
// the image or half hidden does not look like one that moves.
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "slam/settings/slam_settings.h"

namespace viqu::slam {

// An object's features with depth in one frame.
struct ObjectSnapshot {
  int64_t t_ns = 0;
  std::vector<Eigen::Vector3d> p_w;  // positions in the world (map) frame (m)
  std::vector<double> sigma_m;       // depth standard deviation of each (m)
  cv::Mat descriptors;               // CV_8U, one 32-byte row per point
  size_t size() const { return p_w.size(); }
};

struct MotionMeasurement {
  int matches = 0;                   // features matched between the two snapshots
  double lag_s = 0;                  // time between them (s)
  Eigen::Vector3d displacement_w = Eigen::Vector3d::Zero();  // median displacement (m)
  double displacement_m = 0;         // its norm (m)
  double std_error_m = 0;            // standard error of the median (m)
  double threshold_m = 0;            // threshold_m + k_sigma * std_error_m (m)
  bool judged = false;               // enough matches to judge
  bool moving = false;               // judged and displacement_m > threshold
  bool still = false;                // judged, displacement_m + k_sigma * std_error_m < still_max_m, over at
                                     // least half of lag_s: the measurement rules out motion (far, noisy
                                     // objects and short looks are neither moving nor still)
};

// Whether a world point (m) would be in the current image if it had not moved.
using InViewIfStatic = std::function<bool(const Eigen::Vector3d& p_w)>;

// Matches `cur` to `ref` (mutual best Hamming distance within max_hamming, best below 0.8 of the
// second best) and tests the median displacement. Reference points that would be out of the
// current view had they stood still are left out (`in_view` may be empty: all are used): an
// object leaving the image at its edge otherwise matches its remaining part with a look-alike
// part that has left (a person's two legs carry the same texture), a consistent false motion.
MotionMeasurement MeasureMotion(const ObjectSnapshot& ref, const ObjectSnapshot& cur, const AdaptiveDynamicSettings& s,
                                const InViewIfStatic& in_view = {});

// One object's snapshots over the last lag_s and its decision with hold time.
class ObjectMotionTrack {
 public:
  // Adds the frame's snapshot (may be empty: the object was seen without depth) and returns
  // whether the object is dynamic: it moved (by MeasureMotion against a snapshot within lag_s,
  // confirm_frames times in a row to turn dynamic) within the last hold_s, or has not been judged
  // still since it last moved.
  bool Add(ObjectSnapshot snapshot, const AdaptiveDynamicSettings& s, const InViewIfStatic& in_view = {});
  const MotionMeasurement& last() const { return last_; }

 private:
  std::deque<ObjectSnapshot> history_;  // oldest first, all within lag_s of the newest
  MotionMeasurement last_;
  int64_t last_motion_ns_ = 0;
  int consecutive_moving_ = 0;       // judgements of motion in a row
  bool moved_ = false;
  bool static_since_motion_ = false;  // judged still (MotionMeasurement::still) since it last moved
  bool dynamic_ = false;
};

}  // namespace viqu::slam

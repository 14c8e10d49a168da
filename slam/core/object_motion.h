#pragma once
// The `adaptive` dynamic test (a well-posed variant of the paper's eqs. 2-4): does an object move
// in the world? Each frame, the object's features with stereo depth are put in the world frame
// (with a pose from features outside the movable objects when those carry much of the view) and
// matched by descriptor with the object's features of about `lag_s` earlier. The component-wise
// median of the matched points' world displacements, along the object's viewing ray and across
// it, is the object's motion. Each component less `k_sigma` of its standard errors must exceed
// `threshold_m` (as a vector). The noise is that of stereo: along the ray from the depth
// (sigma_z = z^2 * disparity_sigma / bf per point), across it from the keypoint position
// (z * pixel_sigma * level scale / f), tens of times smaller at a few metres, so that motion
// across the view is judged much sooner than motion in depth. Unlike the norm of world positions, this sees
// tangential motion; unlike mask depth, it does not change with the robot's own motion; and unlike
// the mean of whatever points are visible, it compares the same points, so an object sliding out of
// the image or half hidden does not look like one that moves.
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "slam/core/camera.h"
#include "slam/core/silhouette.h"
#include "slam/settings/slam_settings.h"

namespace viqu::slam {

// An object's features with depth in one frame.
struct ObjectSnapshot {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_c_w = Eigen::Isometry3d::Identity();  // the camera's pose, world to camera
  std::vector<Eigen::Vector3d> p_w;  // positions in the world (map) frame (m)
  std::vector<double> sigma_m;       // standard deviation of each along its viewing ray, from depth (m)
  std::vector<double> sigma_lateral_m;  // standard deviation across the ray, from the keypoint position
                                        // (m; empty: as sigma_m, an isotropic error)
  cv::Mat descriptors;               // CV_8U, one 32-byte row per point
  Silhouette silhouette;             // the object's mask (empty: none given)
  double depth_m = 0;                // the object's median depth in the camera (m; 0: no features with depth)
  size_t size() const { return p_w.size(); }
};

struct MotionMeasurement {
  int matches = 0;                   // features matched between the two snapshots
  double lag_s = 0;                  // time between them (s)
  Eigen::Vector3d displacement_w = Eigen::Vector3d::Zero();  // median displacement, along and across the
                                                             // object's viewing ray, in the world frame (m)
  double displacement_m = 0;         // its norm (m)
  Eigen::Vector3d std_error = Eigen::Vector3d::Zero();  // standard errors of the three medians: along
                                                        // the ray, then across it (m)
  double threshold_m = 0;            // the displacement_m beyond which it is moving: threshold_m plus what
                                     // k_sigma standard errors take off each component (m)
  bool judged = false;               // enough matches to judge
  bool too_fast = false;             // not judged: the median displacement is faster than max_speed_mps
                                     // beyond its errors (mismatches)
  bool moving = false;               // judged and displacement_m > threshold
  bool still = false;                // judged, |displacement + k_sigma std errors| < still_max_m, over at
                                     // least half of lag_s: the measurement rules out motion (far, noisy
                                     // objects and short looks are neither moving nor still)
  bool by_silhouette = false;        // moving by the silhouette's shift, not by the features
  double silhouette_m = 0;           // that shift less k_sigma standard errors, at the object's depth (m)
};

// Whether a world point (m) lies in the image, well inside its edges, of a camera at T_c_w.
using InViewIfStatic = std::function<bool(const Eigen::Isometry3d& T_c_w, const Eigen::Vector3d& p_w)>;

// Matches `cur` to `ref` (mutual best Hamming distance within max_hamming, best below 0.8 of the
// second best) and tests the median displacement. A median displacement faster than
// max_speed_mps beyond its errors is a mismatch (a frame whose mask held the background behind
// the object, a jump in stereo depth), not motion: not judged. Points that could not have been
// seen in the other snapshot had they stood still are left out (`in_view` may be empty: all are
// used): the reference points out of the current view, and the current points out of the
// reference view.
// An object leaving the image at its edge otherwise matches its remaining part with a look-alike
// part that has left (a person's two legs carry the same texture), and one entering the image
// matches the part that has just come in with the look-alike part seen before: a consistent
// false motion either way.
MotionMeasurement MeasureMotion(const ObjectSnapshot& ref, const ObjectSnapshot& cur, const AdaptiveDynamicSettings& s,
                                const InViewIfStatic& in_view = {});

// One object's snapshots over the last lag_s and its decision with hold time.
class ObjectMotionTrack {
 public:
  // Adds the frame's snapshot (may be empty: the object was seen without depth) and returns
  // whether the object is dynamic: it moved (by MeasureMotion against a snapshot within lag_s,
  // confirm_frames times in a row to turn dynamic; within hold_s of its release once, or
  // changed_look_frames looks in a row that cannot be judged) within the last hold_s, or has not
  // been judged still since it last moved. Also true while it is tentatively dynamic: its last
  // drop_frames judgements (fewer than confirm_frames) saw motion. Dropping a standing object's
  // features for a frame costs little; keeping a walker's costs the pose, so the features go at
  // the first sign of motion, while the hold and the culling of its map points wait for the
  // confirmation.
  // Before the object is dynamic, a look whose features do not show motion may still show it by its
  // silhouette (MeasureSilhouetteShift against the snapshot nearest silhouette_lag_s earlier; needs
  // `cam`, the snapshots' silhouettes and depths): a walker setting off. Such a look drops the
  // object's features (tentatively) but never confirms it.
  bool Add(ObjectSnapshot snapshot, const AdaptiveDynamicSettings& s, const InViewIfStatic& in_view = {},
           const StereoCamera* cam = nullptr);
  // Dynamic by a confirmed judgement (not merely tentatively).
  bool confirmed() const { return dynamic_; }
  // The earliest its latest motion can have begun (ns): the later of the start of the first look
  // in the run of looks of motion that made it dynamic (a look compares with a snapshot up to
  // lag_s earlier: the object stood where that snapshot saw it until then) and the end of the last
  // look before that run judged still with a median displacement under stop_max_m (it stood
  // within a centimetre until then). 0 before any.
  int64_t motion_onset_ns() const { return motion_onset_ns_; }
  const MotionMeasurement& last() const { return last_; }
  // Forgets the snapshots (not the decision, its hold or the time of the last motion): after the
  // world frame has changed under them (a new map segment, a relocalisation), world positions
  // before and after differ by the pose jump, which is no motion of the object.
  void RestartMeasurements();

 private:
  struct Past {
    ObjectSnapshot snapshot;
    int jumps_to_next = -1;  // 1 when the next snapshot differs from it faster than max_speed_mps (a
                             // transient mismatch), 0 when not, -1 not yet measured
  };
  // When the object last stood (ns), for the onset of the motion that this look confirms: the
  // still look's end, moved back along the displacement's growth to where it meets zero.
  int64_t UnmovedUntilNs(int64_t t_ns) const;
  // The silhouette's look (see Add): makes last_ a look of motion when the mask moved.
  void LookAtSilhouette(const ObjectSnapshot& snapshot, const AdaptiveDynamicSettings& s, const StereoCamera* cam);

  std::deque<Past> history_;  // oldest first, all within lag_s of the newest
  MotionMeasurement last_;
  int64_t last_motion_ns_ = 0;      // end of the last look that saw motion, or the start of a later
                                     // still look that overlaps it: the latest the motion can have been
  int64_t last_motion_ref_ns_ = 0;   // start of the last look that saw motion
  int64_t released_ns_ = -1;         // when it last turned from dynamic to static (-1: never)
  int consecutive_moving_ = 0;       // judgements of motion in a row
  int64_t run_start_ns_ = 0;         // start of the first look of that run
  int64_t last_unmoved_ns_ = 0;      // end of the last look judged still within stop_max_m
  int64_t last_unmoved_ref_ns_ = 0;  // its start
  double last_unmoved_m_ = 0;        // its median displacement (m)
  int64_t motion_onset_ns_ = 0;      // see motion_onset_ns()
  int unjudged_after_release_ = 0;   // looks in a row within hold_s of the release that could not be judged
  bool moved_ = false;
  bool static_since_motion_ = false;  // judged still (MotionMeasurement::still) since it last moved
  bool dynamic_ = false;
};

}  // namespace viqu::slam

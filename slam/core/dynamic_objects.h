#pragma once
// The dynamic-object stage (paper Section III-B): every movable object (person, box, ball) in the
// segmentation masks is followed by its instance id and judged static or dynamic by the method of
// `dynamic.method`; the features of dynamic objects are removed before tracking and mapping.
//
//   KeepMask()  before tracking: which features stay (judgements of the earlier frames);
//   Update()    after tracking, with the frame's pose: judges each object again and returns the
//               objects that have just turned dynamic (the caller culls their map points).
//
// An object keeps its history through missed detections; unseen for `forget_s` it starts anew.
// Furniture is static by category; background and the robot's own body are never judged.
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "slam/core/camera.h"
#include "slam/core/dynamic_attribute.h"
#include "slam/core/frame.h"
#include "slam/core/object_motion.h"
#include "slam/measurements/stereo_frame.h"
#include "slam/settings/slam_settings.h"

namespace viqu::slam {

enum class DynamicMethod { kNone, kSemantic, kPaper, kAdaptive };
// A motion onset before any time: an object whose motion is not dated loses every observation.
constexpr int64_t kUndatedMotion = std::numeric_limits<int64_t>::min();
// From the settings' mode and dynamic.method (mode visual: kNone).
DynamicMethod DynamicMethodOf(const SlamSettings& s);
// Person, box, ball: the categories a detector reports as possibly moving.
bool IsMovable(Category c);

// One object in one frame.
struct ObjectReport {
  uint16_t id = 0;                 // instance id
  std::string name;                // instance name
  Category category = Category::kBackground;
  int features = 0;                // features inside its mask (before removal)
  int dropped = 0;                 // of those, removed before tracking, or all of them when the object
                                   // turned dynamic on this frame (DropFromFrame: its pose is optimised
                                   // again without them)
  bool dynamic = false;            // judged dynamic after this frame
  double score = 0;                // adaptive: median displacement (m); paper: change of A (m)
  double threshold = 0;            // the score's threshold (m)
};

class DynamicObjects {
 public:
  DynamicObjects(const SlamSettings& settings, const StereoCamera& cam);

  DynamicMethod method() const { return method_; }
  // The paper's method labels map points by their projection (Update's `map_points_w`).
  bool NeedsMapPoints() const { return method_ == DynamicMethod::kPaper; }
  // Paper and adaptive judge with the frame's pose (semantic and none do not).
  bool NeedsPose() const { return method_ == DynamicMethod::kPaper || method_ == DynamicMethod::kAdaptive; }

  // Starts a frame: one report per movable instance of `instances` present in `f`, and the
  // features to keep (false: on an object judged dynamic; semantic: on any movable object).
  std::vector<bool> KeepMask(const FrameFeatures& f, const std::vector<SegmentInstance>& instances);

  // Judges the frame's objects with `T_c_w` (map to camera) and the features `f` (all of them,
  // labelled). `instance_id` (CV_16U; may be empty) marks the masks' edges; `map_points_w` serve
  // the paper's method only. Returns
  // the ids that have turned dynamic with this frame (tentatively or confirmed; see
  // ObjectMotionTrack::Add).
  // `T_c_w_tracked` (may be null: T_c_w) is the tracked pose, from every feature kept, with which
  // the adaptive test carries masks between frames.
  std::vector<uint16_t> Update(int64_t t_ns, const FrameFeatures& f, const cv::Mat& instance_id,
                               const Eigen::Isometry3d& T_c_w, const std::vector<Eigen::Vector3d>& map_points_w,
                               const Eigen::Isometry3d* T_c_w_tracked = nullptr);

  // The world frame has jumped (a relocalisation, a new map segment): the objects' motion
  // measurements start again; their decisions stand.
  void RestartMeasurements();

  // The ids whose dynamic decision was confirmed with the last Update (their map points go; a
  // tentative decision keeps them). Semantic and paper decisions are confirmed when made.
  const std::vector<uint16_t>& JustConfirmed() const { return just_confirmed_; }
  // For an object of JustConfirmed(): the earliest its motion can have begun (ns; adaptive,
  // ObjectMotionTrack::motion_onset_ns). Semantic and paper decisions do not date the motion:
  // kUndatedMotion.
  int64_t MotionOnsetNs(uint16_t id) const;

  // The reports of the current frame, in id order.
  const std::vector<ObjectReport>& reports() const { return reports_; }
  // The frame's features on these objects were taken out of its pose after the judgement
  // (Tracker::ReposeWithout): their reports count them all as dropped.
  void DropFromFrame(const std::vector<uint16_t>& ids);

 private:
  struct ObjectState {
    int64_t last_seen_ns = 0;
    bool dynamic = false;          // features dropped: confirmed or tentatively dynamic
    bool confirmed = false;        // dynamic by a confirmed decision
    ObjectMotionTrack motion;      // adaptive
    PaperAttributeSeries paper;    // paper
  };
  // The object's features with depth, inside its mask by at least adaptive.interior_px (when
  // `instance_id` is given), within its depth band, in the world frame.
  ObjectSnapshot Snapshot(int64_t t_ns, const FrameFeatures& f, uint16_t id, const cv::Mat& instance_id,
                          const Eigen::Isometry3d& T_w_c) const;
  // Eq. 2's w_bar per object id: mean norm of the map points whose projection falls in its mask.
  std::map<uint16_t, double> LabelledPointNorms(const cv::Mat& instance_id, const Eigen::Isometry3d& T_c_w,
                                                const std::vector<Eigen::Vector3d>& map_points_w) const;

  DynamicSettings settings_;
  DynamicMethod method_;
  StereoCamera cam_;
  std::map<uint16_t, ObjectState> objects_;
  std::vector<ObjectReport> reports_;
  std::vector<uint16_t> just_confirmed_;
};

}  // namespace viqu::slam

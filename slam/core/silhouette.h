#pragma once
// An object's silhouette in the instance image, and how far it moved across the view between two
// frames once the camera's own motion is taken out.
//
// A walker who sets off moves its body 4 cm a frame at 0.8 m/s, but the features matched on it
// over time sit mostly on the stance leg, which stands still or moves back, so their median
// displacement shows a third of that (standing_people: 2 cm after 0.1 s). The mask moves with
// the body. Each row of the silhouette (every kSilhouetteRowStep-th row) gives the two ends of the
// object's extent in that row; an end counts where it is the object's own edge, away from the
// image's edges: where it meets the background or an instance behind it. An end that meets a nearer
// instance is where that one hides it (a walker in front uncovering a standing person moves that
// person's visible edge; people standing in a row overlap), and an end at the image's edge is where
// the object leaves the view. The reference silhouette's ends are carried into the current view as
// if the object stood still at its depth, and the median difference from the current ends of the
// same side is its motion across the view, in pixels.
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "slam/core/camera.h"

namespace viqu::slam {

// Rows sampled (every second row: the centres of neighbouring rows differ by less than the
// masks' noise; halves the cost).
constexpr int kSilhouetteRowStep = 2;

struct Silhouette {
  // Rows where at least one end of the object's extent is its own edge (it meets the background
  // or an instance behind it) away from the image's edges: row, leftmost and rightmost column
  // (px; -1: that end does not count).
  std::vector<int> v, lo, hi;
  // Other instances met at the left and at the right ends that may hide the object, and every
  // instance in the frame (sorted): a missed detection of a neighbour turns its border with the
  // object into background, a false free end, so a side is compared only when the neighbours met
  // on that side in each frame are present in the other frame.
  std::vector<uint16_t> touches_lo, touches_hi, frame_ids;
  // The camera's pose (world to camera) the silhouette is carried with: the tracked pose, from
  // every feature kept (the pose from the static scene alone, with which features are judged, errs
  // by up to a degree where people carry most of the view: 6 px, 2-3 cm at their distance).
  Eigen::Isometry3d T_c_w = Eigen::Isometry3d::Identity();
  bool empty() const { return v.empty(); }
  // Index of row `row` in v (-1: not a usable row of the silhouette).
  int RowIndex(int row) const;
};

// The silhouettes of `ids` in `instance_id` (CV_16U), one pass over every kSilhouetteRowStep-th row.
// Ends within `border_px` of the image's left or right edge do not count. An end that meets another
// instance counts when that instance lies more than `behind_m` behind the object (`depth_m`: median
// depth per instance id, m; an instance without one is taken to be in front).
std::map<uint16_t, Silhouette> ExtractSilhouettes(const cv::Mat& instance_id, const std::set<uint16_t>& ids,
                                                  int border_px, const std::map<uint16_t, double>& depth_m = {},
                                                  double behind_m = 0);

// A detector's mask is loose and flickers: it grows by a few pixels more or less from frame to
// frame, moving its left ends left and its right ends right by the same amount. With both sides
// seen, the mean of the two sides' median shifts cancels that growth; one side alone cannot tell
// it from motion (`two_sided` false).
struct SilhouetteShift {
  int rows = 0;             // row ends compared, both sides
  double shift_px = 0;      // motion across the view, current minus carried (px)
  double std_error_px = 0;  // its standard error, from the rows' spread (px)
  bool two_sided = false;   // both sides had at least min_side_rows ends: the mask's growth cancels
};

// Carries `ref` (seen at depth `z_ref`, m) into the current camera (by the two silhouettes' poses)
// as if it stood still, and compares its free row ends with `cur`'s. A side is left out when an
// instance that meets the object on that side in one frame is missing from the other (a person
// uncovered by a walker setting off appears at the walker's trailing side only), or when it has
// fewer than `min_side_rows` ends.
SilhouetteShift MeasureSilhouetteShift(const Silhouette& ref, double z_ref, const Silhouette& cur, const StereoCamera& cam,
                                       int min_side_rows);

}  // namespace viqu::slam

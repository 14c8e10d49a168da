#pragma once
// Stereo correspondences on a rectified pair: for each left feature, the right features in a band
// of rows around it, with a disparity in range, are compared by descriptor (Hamming distance);
// the best is refined by sum-of-absolute-differences patch matching along the row at the
// feature's pyramid level and a parabola through the SAD minimum for sub-pixel disparity. A left
// feature with no right keypoint at its corner is searched by SAD along the whole row range and
// kept if the minimum is unique.
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

namespace viqu::slam {

struct StereoMatcherOptions {
  int max_hamming = 75;          // accept the best descriptor match below this distance (bits)
  double row_band_px = 2.0;      // rows searched above and below, times the level's scale (px)
  int sad_half_window = 5;       // SAD patch half size at the feature's level (px)
  int sad_search_px = 5;         // SAD search range around the descriptor match (px at the level)
  double max_ratio = 0.95;        // best distance must be below this times the second best
  double min_depth_m = 0.1;      // nearer points are rejected (m)
  double max_depth_baselines = 40;  // depth only for points closer than this many baselines
  double scale_factor = 1.2;     // pyramid scale between levels (as the extractor's)
  double sad_outlier_factor = 2.1;  // matches whose SAD exceeds this times the median are dropped
  double sad_uniqueness = 0.7;   // a row search without a descriptor match needs its SAD minimum
                                 // below this times the best SAD more than 2 px away
  // Sub-pixel disparity from the SAD costs at the best column and its two neighbours: "parabola"
  // (a parabola through the three) or "equiangular" (two lines of equal and opposite slope, the
  // shape of an SAD cost near its minimum; a parabola pulls the estimate towards whole pixels).
  std::string subpixel = "parabola";
  // Slanted surfaces: the ground seen from a low camera changes disparity by about half a pixel
  // per row, so an upright window mixes rows of different disparity. The refinement also tries
  // windows whose rows are shifted by shear x row offset (px of disparity per row, at the level),
  // shear in [-max_shear, max_shear] in steps of shear_step; 0 keeps the upright window only.
  double max_shear = 0;
  double shear_step = 0.2;
  // Left-right check: the right patch at the match is searched back along the left row over the
  // whole disparity range (the same window, upright or sheared); the match is dropped when the
  // sub-pixel column found there is further than this from where the forward match says it lies
  // (px at the feature's level; 0: off). Catches matches that are not mutual (ambiguous texture,
  // occlusion).
  double lr_check_px = 0;
  // Not the matcher's: observations whose stereo depth is below this many baselines enter pose
  // optimisation and local BA with their right-image column weighted as below, or by their
  // left-image position only where the weight is 0 (their depth still places new map points;
  // 0: every stereo observation keeps its right-image column at full weight). 8.75 is 0.35 m on the
  // rat: its near floor's stereo leans near (docs/MEASURED.md, sessions 41-43).
  double near_mono_baselines = 8.75;
  // The weight (information, 1 / sigma^2, relative to a far observation's) of those near
  // observations' right-image column in the tracker's pose optimisation and in local BA; 0
  // leaves it out.
  double near_right_weight_tracking = 1;
  double near_right_weight_ba = 0.03;
  bool level_pixel_centres = false;  // the extractor's mapping of level pixels (orb.level_pixel_centres)
};

struct StereoMatch {
  int right_index = -1;          // index into the right keypoints; -1 if unmatched or found by
                                 // the row search without a right keypoint (u_right says which)
  float u_right = -1;            // sub-pixel column in the right image (px), -1 if unmatched
  float depth_m = -1;            // depth along the optical axis (m), -1 if unmatched or too far
};

class StereoMatcher {
 public:
  explicit StereoMatcher(const StereoMatcherOptions& opt = {}) : opt_(opt) {}

  // One StereoMatch per left keypoint. fx (px) and baseline (m) give depth = fx * b / disparity.
  std::vector<StereoMatch> Match(const cv::Mat& left_grey, const cv::Mat& right_grey,
                                 const std::vector<cv::KeyPoint>& left_kps, const cv::Mat& left_desc,
                                 const std::vector<cv::KeyPoint>& right_kps, const cv::Mat& right_desc,
                                 double fx, double baseline_m) const;

 private:
  StereoMatcherOptions opt_;
};

}  // namespace viqu::slam

#pragma once
// One tracked image: its features with stereo depth, a grid for searching features by area, the
// map points matched to them and the camera pose. Keyframes keep the frame's features by sharing
// the same FrameFeatures.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "slam/core/camera.h"

namespace viqu::slam {

class MapPoint;

// Where a feature lies: all that tracking and mapping read of cv::KeyPoint once the descriptors
// are computed (12 bytes against 28; a keyframe keeps one per feature for the rest of the run).
struct FeaturePoint {
  cv::Point2f pt;  // level-0 pixel coordinates
  int octave = 0;  // pyramid level
  FeaturePoint() = default;
  FeaturePoint(cv::Point2f pt, int octave) : pt(pt), octave(octave) {}
};

// The place and level of each keypoint, in a vector of exactly their number.
std::vector<FeaturePoint> ToFeaturePoints(const std::vector<cv::KeyPoint>& keypoints);

// Features of one left image; immutable once built.
struct FrameFeatures {
  static constexpr int kCellPx = 16;   // search grid cell (px)

  std::vector<FeaturePoint> keypoints; // level-0 pixel coordinates and pyramid level
  cv::Mat descriptors;                 // CV_8U, 32 bytes a row
  std::vector<float> u_right;          // column in the right image, -1 if no stereo match
  std::vector<float> depth;            // stereo/RGB-D depth (m), -1 if none
  std::vector<uint16_t> object;        // segmentation instance id under the feature (0 = none)
  std::vector<float> level_sigma2;     // squared scale of each pyramid level
  std::vector<float> level_scale;      // scale of each pyramid level
  int grid_cols = 0, grid_rows = 0;
  // Feature indices per cell, row-major, in one array: cell c holds
  // grid_index[grid_start[c] .. grid_start[c + 1]) (a list per cell cost about 60 kB a keyframe).
  std::vector<int> grid_start, grid_index;

  size_t size() const { return keypoints.size(); }
  void BuildGrid(int width, int height);
  // Features within `radius` px of (u, v) whose level is in [min_level, max_level] (-1: any).
  std::vector<int> InArea(double u, double v, double radius, int min_level = -1, int max_level = -1) const;
  // The same into `out` (cleared first): a caller that keeps one vector allocates once.
  void InArea(double u, double v, double radius, int min_level, int max_level, std::vector<int>* out) const;
  // Sets `object` from a CV_16U instance image of the image size (empty: every feature 0).
  void LabelObjects(const cv::Mat& instance_id);
  // The features whose `keep` entry is true, in order, with their grid rebuilt.
  std::shared_ptr<FrameFeatures> Subset(const std::vector<bool>& keep, int width, int height) const;
  Eigen::Vector3d Unproject(const StereoCamera& cam, int i) const {
    return cam.Unproject(keypoints[i].pt.x, keypoints[i].pt.y, depth[i]);
  }
};

struct Frame {
  int64_t t_ns = 0;
  std::shared_ptr<const FrameFeatures> features;
  std::vector<MapPoint*> points;       // matched map point per feature (nullptr: none)
  std::vector<bool> outlier;           // rejected by pose optimisation
  Eigen::Isometry3d T_c_w = Eigen::Isometry3d::Identity();  // world -> camera

  void Reset(std::shared_ptr<const FrameFeatures> f) {
    features = std::move(f);
    points.assign(features->size(), nullptr);
    outlier.assign(features->size(), false);
  }
  size_t size() const { return points.size(); }
  Eigen::Vector3d Center() const { return T_c_w.inverse().translation(); }
  int MatchedCount() const;
  // Unmatches every feature.
  void ClearMatches() {
    std::fill(points.begin(), points.end(), nullptr);
    std::fill(outlier.begin(), outlier.end(), false);
  }
  // Unmatches the features that pose optimisation rejected.
  void ForgetOutliers();
};

}  // namespace viqu::slam

#pragma once
// The rectified stereo camera as the tracker sees it: pinhole intrinsics of the left camera and
// bf = fx * baseline, which turns depth into the column of the same point in the right image.
#include <Eigen/Core>

namespace viqu::slam {

struct StereoCamera {
  int width = 0, height = 0;       // (px)
  double fx = 0, fy = 0, cx = 0, cy = 0;  // (px)
  double bf = 0;                   // fx * baseline (px m); the virtual baseline for RGB-D input
  double close_depth_m = 0;        // points nearer than this have reliable stereo depth (m)
  // Observations with a stereo depth below this enter pose optimisation and local BA with their
  // right-image column's residual scaled by near_right_scale, or without that column where the
  // scale is 0 (m; 0: none). stereo.near_mono_baselines times the baseline.
  double mono_below_depth_m = 0;
  // sqrt(stereo.near_right_weight_tracking, or _ba in the local mapper's copy): scales that row's
  // residual and Jacobian.
  double near_right_scale = 0;
  // The right-image column an optimiser should use for an observation (-1: monocular).
  float OptimiserColumn(float u_right, float depth) const {
    return depth < mono_below_depth_m && near_right_scale == 0 ? -1.f : u_right;
  }
  // The scale of that column's residual row (1 beyond the cut).
  double RightScale(float depth) const { return depth < mono_below_depth_m ? near_right_scale : 1.0; }

  Eigen::Vector2d Project(const Eigen::Vector3d& p_c) const {
    return {fx * p_c.x() / p_c.z() + cx, fy * p_c.y() / p_c.z() + cy};
  }
  // Column of the point in the right image.
  double ProjectRight(const Eigen::Vector3d& p_c) const { return fx * p_c.x() / p_c.z() + cx - bf / p_c.z(); }
  Eigen::Vector3d Unproject(double u, double v, double depth) const {
    return {(u - cx) / fx * depth, (v - cy) / fy * depth, depth};
  }
  bool InImage(double u, double v) const { return u >= 0 && v >= 0 && u <= width - 1 && v <= height - 1; }
};

}  // namespace viqu::slam

#pragma once
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "slam/io/camera_calibration.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// Rectifies a calibrated stereo pair to row-aligned pinhole images (cv::stereoRectify with zero
// disparity at infinity, alpha 0: every output pixel sees the scene, output size = input size).
//
// Frames: cam0/cam1 are the raw optical frames, rect0/rect1 the rectified ones. Rectification
// rotates each camera about its centre: p_rect0 = R1 * p_cam0, so the rectified left camera's
// pose is T_cam0_rect0 = [R1^T | 0] and a pose T_w_cam0 becomes T_w_rect0 = T_w_cam0 * R1^T.
// rect1 sits at +baseline along rect0's x axis with the same orientation and intrinsics.
class StereoRectifier {
 public:
  // `T_cam0_cam1`: the right camera in the left camera's frame (m). The right camera must lie
  // mainly along +x of the left one; otherwise InputError("<name>: ...").
  StereoRectifier(const CameraCalibration& cam0, const CameraCalibration& cam1,
                  const Eigen::Isometry3d& T_cam0_cam1, const std::string& name);

  // Raw images (any 8-bit type, the calibrated size) to rectified ones (same type).
  void Rectify(const cv::Mat& raw0, const cv::Mat& raw1, cv::Mat* rect0, cv::Mat* rect1) const;
  // A raw left image of labels (e.g. CV_16U instance ids, the calibrated size) to the rectified
  // left geometry by nearest neighbour (values are never blended; outside the raw image: 0).
  cv::Mat RectifyLeftLabels(const cv::Mat& raw0) const;

  const PinholeIntrinsics& intrinsics() const { return intrinsics_; }  // of rect0 and rect1
  double baseline_m() const { return baseline_m_; }
  // T_cam0_rect0: rotation R1^T, no translation.
  const Eigen::Isometry3d& T_cam0_rect0() const { return T_cam0_rect0_; }

 private:
  PinholeIntrinsics intrinsics_;
  double baseline_m_ = 0;
  Eigen::Isometry3d T_cam0_rect0_ = Eigen::Isometry3d::Identity();
  cv::Mat map0_a_, map0_b_, map1_a_, map1_b_;  // cv::remap maps (CV_16SC2 + CV_16UC1)
  // Left maps in floating point (CV_32FC1 x, y): nearest neighbour rounds to the nearest raw
  // pixel with these, whereas the fixed-point maps would truncate.
  cv::Mat map0_x_, map0_y_;
};

}  // namespace viqu::io

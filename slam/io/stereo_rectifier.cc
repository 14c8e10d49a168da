#include "slam/io/stereo_rectifier.h"

#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"

namespace viqu::io {
namespace {

cv::Mat CameraMatrix(const PinholeIntrinsics& k) {
  return (cv::Mat_<double>(3, 3) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
}

cv::Mat Distortion(const CameraCalibration& c) {
  if (c.distortion.empty()) return cv::Mat();
  return cv::Mat(c.distortion, /*copyData=*/true).reshape(1, 1);
}

}  // namespace

StereoRectifier::StereoRectifier(const CameraCalibration& cam0, const CameraCalibration& cam1,
                                 const Eigen::Isometry3d& T_cam0_cam1, const std::string& name) {
  if (cam0.pinhole.width != cam1.pinhole.width || cam0.pinhole.height != cam1.pinhole.height) {
    throw InputError(name + ": the two cameras have different resolutions");
  }
  const Eigen::Vector3d t01 = T_cam0_cam1.translation();
  if (!(t01.x() > 0 && std::abs(t01.x()) > std::abs(t01.y()) && std::abs(t01.x()) > std::abs(t01.z()))) {
    throw InputError(name + ": the right camera is not to the right of the left one (position in the left "
                     "camera frame: " + std::to_string(t01.x()) + ", " + std::to_string(t01.y()) + ", " +
                     std::to_string(t01.z()) + " m)");
  }
  // OpenCV wants the transform from cam0 to cam1 coordinates: p_cam1 = R p_cam0 + T.
  const Eigen::Isometry3d T_cam1_cam0 = T_cam0_cam1.inverse();
  cv::Mat R(3, 3, CV_64F), T(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.at<double>(r, c) = T_cam1_cam0.linear()(r, c);
    T.at<double>(r, 0) = T_cam1_cam0.translation()(r);
  }
  const cv::Size size(cam0.pinhole.width, cam0.pinhole.height);
  const cv::Mat K0 = CameraMatrix(cam0.pinhole), K1 = CameraMatrix(cam1.pinhole);
  const cv::Mat D0 = Distortion(cam0), D1 = Distortion(cam1);
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(K0, D0, K1, D1, size, R, T, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0.0, size);
  if (std::abs(P2.at<double>(1, 3)) > 1e-9 * std::abs(P2.at<double>(0, 3)) || !(P2.at<double>(0, 0) > 0)) {
    throw InputError(name + ": stereo rectification did not give a horizontal pair");
  }
  intrinsics_.width = size.width;
  intrinsics_.height = size.height;
  intrinsics_.fx = P1.at<double>(0, 0);
  intrinsics_.fy = P1.at<double>(1, 1);
  intrinsics_.cx = P1.at<double>(0, 2);
  intrinsics_.cy = P1.at<double>(1, 2);
  baseline_m_ = -P2.at<double>(0, 3) / P2.at<double>(0, 0);
  if (!(baseline_m_ > 0)) throw InputError(name + ": rectified baseline is not positive");
  Eigen::Matrix3d R_rect0_cam0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_rect0_cam0(r, c) = R1.at<double>(r, c);
  }
  T_cam0_rect0_.linear() = R_rect0_cam0.transpose();
  cv::initUndistortRectifyMap(K0, D0, R1, P1, size, CV_16SC2, map0_a_, map0_b_);
  cv::initUndistortRectifyMap(K1, D1, R2, P2, size, CV_16SC2, map1_a_, map1_b_);
  cv::initUndistortRectifyMap(K0, D0, R1, P1, size, CV_32FC1, map0_x_, map0_y_);
}

void StereoRectifier::Rectify(const cv::Mat& raw0, const cv::Mat& raw1, cv::Mat* rect0, cv::Mat* rect1) const {
  cv::remap(raw0, *rect0, map0_a_, map0_b_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  cv::remap(raw1, *rect1, map1_a_, map1_b_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
}

cv::Mat StereoRectifier::RectifyLeftLabels(const cv::Mat& raw0) const {
  cv::Mat rect0;
  cv::remap(raw0, rect0, map0_x_, map0_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
  return rect0;
}

}  // namespace viqu::io

#include "slam/io/image_undistorter.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace viqu::io {

ImageUndistorter::ImageUndistorter(const CameraCalibration& camera) {
  const PinholeIntrinsics& k = camera.pinhole;
  const cv::Mat K = (cv::Mat_<double>(3, 3) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  cv::Mat D;
  if (!camera.distortion.empty()) cv::Mat(camera.distortion, /*copyData=*/true).reshape(1, 1).copyTo(D);
  cv::initUndistortRectifyMap(K, D, cv::Mat(), K, cv::Size(k.width, k.height), CV_32FC1, map_x_, map_y_);
}

cv::Mat ImageUndistorter::Colour(const cv::Mat& raw) const {
  cv::Mat out;
  cv::remap(raw, out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  return out;
}

cv::Mat ImageUndistorter::Depth(const cv::Mat& raw) const {
  cv::Mat out;
  cv::remap(raw, out, map_x_, map_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  return out;
}

}  // namespace viqu::io

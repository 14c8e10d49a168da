#pragma once
#include <opencv2/core/mat.hpp>

#include "slam/io/camera_calibration.h"

namespace viqu::io {

// Removes radial-tangential distortion from single-camera images, keeping the camera matrix
// (the output is the ideal pinhole camera with the calibration's intrinsics and size). Used for
// TUM freiburg1/2, whose RGB and registered depth images are distorted.
class ImageUndistorter {
 public:
  explicit ImageUndistorter(const CameraCalibration& camera);

  // Colour or grey image: bilinear interpolation.
  cv::Mat Colour(const cv::Mat& raw) const;
  // Depth (or any image whose values must not be mixed): nearest neighbour.
  cv::Mat Depth(const cv::Mat& raw) const;

 private:
  cv::Mat map_x_, map_y_;  // CV_32FC1 maps from output to raw pixels
};

}  // namespace viqu::io

#pragma once
// Reading the image files of a dataset. Failures return an empty Mat and say why, so that the
// reader decides between skipping the frame and stopping (see FrameSkipPolicy).
#include <string>

#include <opencv2/core/mat.hpp>

namespace viqu::io {

// An 8-bit image (grey, BGR or BGRA as stored). Empty, with *why set, when the file is missing,
// cannot be decoded or is not 8-bit.
cv::Mat ReadImage8(const std::string& path, std::string* why);

// A 16-bit single-channel image (depth, instance ids). Empty, with *why set, otherwise.
cv::Mat ReadImage16(const std::string& path, std::string* why);

// RGB (CV_8UC3) from an 8-bit grey, BGR or BGRA image.
cv::Mat ToRgb(const cv::Mat& image8);

// Metric depth (CV_32F, m) from a 16-bit depth image: value * unit_m; 0 stays 0 (no depth).
cv::Mat DepthToMetres(const cv::Mat& depth16, double unit_m);

}  // namespace viqu::io

#include "slam/io/image_files.h"

#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace viqu::io {
namespace {

cv::Mat Decode(const std::string& path, std::string* why) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    *why = path + ": image file not found";
    return {};
  }
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    image.release();
  }
  if (image.empty()) *why = path + ": cannot decode the image (corrupt or not an image)";
  return image;
}

}  // namespace

cv::Mat ReadImage8(const std::string& path, std::string* why) {
  cv::Mat image = Decode(path, why);
  if (image.empty()) return image;
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3 && image.channels() != 4)) {
    *why = path + ": expected an 8-bit grey or colour image";
    return {};
  }
  return image;
}

cv::Mat ReadImage16(const std::string& path, std::string* why) {
  cv::Mat image = Decode(path, why);
  if (image.empty()) return image;
  if (image.type() != CV_16UC1) {
    *why = path + ": expected a 16-bit single-channel image";
    return {};
  }
  return image;
}

cv::Mat ToRgb(const cv::Mat& image8) {
  cv::Mat rgb;
  switch (image8.channels()) {
    case 1: cv::cvtColor(image8, rgb, cv::COLOR_GRAY2RGB); break;
    case 4: cv::cvtColor(image8, rgb, cv::COLOR_BGRA2RGB); break;
    default: cv::cvtColor(image8, rgb, cv::COLOR_BGR2RGB); break;
  }
  return rgb;
}

cv::Mat DepthToMetres(const cv::Mat& depth16, double unit_m) {
  cv::Mat metres;
  depth16.convertTo(metres, CV_32F, unit_m);
  return metres;
}

}  // namespace viqu::io

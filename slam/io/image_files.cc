#include "slam/io/image_files.h"

#include <filesystem>
#include <fstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/io/png_check.h"

namespace viqu::io {
namespace {

// The largest image file read (bytes): a 4K 16-bit RGB frame is 50 MB uncompressed.
constexpr uintmax_t kMaxImageFileBytes = uintmax_t{256} << 20;

cv::Mat Decode(const std::string& path, std::string* why) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    *why = path + ": image file not found";
    return {};
  }
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxImageFileBytes) {
    *why = path + ": image file larger than 256 MiB or unreadable";
    return {};
  }
  std::string bytes(static_cast<size_t>(size), '\0');
  std::ifstream in(path, std::ios::binary);
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    *why = path + ": cannot read the image file";
    return {};
  }
  // PNG damage is found before libpng sees it, which would print its own error first.
  if (LooksLikePng(bytes)) {
    const std::string problem = PngStructureProblem(bytes);
    if (!problem.empty()) {
      *why = path + ": corrupt PNG (" + problem + ")";
      return {};
    }
  }
  cv::Mat image;
  try {
    image = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, bytes.data()), cv::IMREAD_UNCHANGED);
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

#pragma once
// Where a pixel of a pyramid level lies in the full image. Level l is the image resized by
// cv::resize (INTER_LINEAR) to cvRound(cols / s) x cvRound(rows / s), s = scale_factor^l, and
// resize samples level pixel x at image coordinate (x + 0.5) * cols / level_cols - 0.5: the
// level's true scale is cols / level_cols (not s: 640 / 533 = 1.2008 at level 1), and its pixel
// centres sit half a level pixel in. Mapping by x * s instead shifts a level's features by up to
// (s - 1) / 2 px (1.3 px at level 7) and shrinks them towards the top-left corner.
#include <opencv2/core/types.hpp>

namespace viqu::slam {

class PyramidLevel {
 public:
  // The level of an image of `image` size at scale `scale` (>= 1).
  PyramidLevel(cv::Size image, double scale)
      : size_(cvRound(image.width / scale), cvRound(image.height / scale)),
        sx_(static_cast<double>(image.width) / size_.width),
        sy_(static_cast<double>(image.height) / size_.height) {}

  cv::Size size() const { return size_; }
  double scale_x() const { return sx_; }  // image pixels per level pixel along a row
  double scale_y() const { return sy_; }

  double ToImageX(double x) const { return (x + 0.5) * sx_ - 0.5; }
  double ToImageY(double y) const { return (y + 0.5) * sy_ - 0.5; }
  double ToLevelX(double u) const { return (u + 0.5) / sx_ - 0.5; }
  double ToLevelY(double v) const { return (v + 0.5) / sy_ - 0.5; }
  cv::Point2f ToImage(cv::Point2f p) const {
    return {static_cast<float>(ToImageX(p.x)), static_cast<float>(ToImageY(p.y))};
  }

 private:
  cv::Size size_;
  double sx_, sy_;
};

}  // namespace viqu::slam

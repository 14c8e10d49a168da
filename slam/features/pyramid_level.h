#pragma once
// Where a pixel of a pyramid level lies in the full image. Level l is the image resized by
// cv::resize (INTER_LINEAR) to cvRound(cols / s) x cvRound(rows / s), s = scale_factor^l, and
// resize samples level pixel x at image coordinate (x + 0.5) * cols / level_cols - 0.5: the
// level's true scale is cols / level_cols (not s: 640 / 533 = 1.2008 at level 1), and its pixel
// centres sit half a level pixel in. Mapping by x * s instead (ORB-SLAM's and OpenCV's
// convention, `pixel_centres` false) shifts a level's features by up to (s - 1) / 2 px (1.3 px at
// level 7) and shrinks them towards the top-left corner.
#include <opencv2/core/types.hpp>

namespace viqu::slam {

class PyramidLevel {
 public:
  // The level of an image of `image` size at scale `scale` (>= 1), its pixels mapped to the image
  // as resize samples them (`pixel_centres`) or by x * scale.
  PyramidLevel(cv::Size image, double scale, bool pixel_centres = true)
      : size_(cvRound(image.width / scale), cvRound(image.height / scale)),
        sx_(pixel_centres ? static_cast<double>(image.width) / size_.width : scale),
        sy_(pixel_centres ? static_cast<double>(image.height) / size_.height : scale),
        offset_(pixel_centres ? 0.5 : 0.0) {}

  cv::Size size() const { return size_; }
  double scale_x() const { return sx_; }  // image pixels per level pixel along a row

  double ToImageX(double x) const { return (x + offset_) * sx_ - offset_; }
  double ToImageY(double y) const { return (y + offset_) * sy_ - offset_; }
  double ToLevelX(double u) const { return (u + offset_) / sx_ - offset_; }
  double ToLevelY(double v) const { return (v + offset_) / sy_ - offset_; }
  cv::Point2f ToImage(cv::Point2f p) const {
    return {static_cast<float>(ToImageX(p.x)), static_cast<float>(ToImageY(p.y))};
  }

 private:
  cv::Size size_;
  double sx_, sy_;  // image pixels per level pixel
  double offset_;   // 0.5 with pixel centres, 0 by x * scale
};

}  // namespace viqu::slam

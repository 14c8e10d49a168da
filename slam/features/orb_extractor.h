#pragma once
// ORB features spread over the whole image: a scale pyramid, FAST corners detected per grid cell
// with an adaptive threshold (a cell that yields nothing at the initial threshold is searched
// again at a lower one), cells served round-robin by corner response until each level's quota is
// met, intensity-centroid orientation, and rotated BRIEF descriptors. OpenCV's plain ORB keeps
// the strongest corners of the whole image, which cluster on a few textured patches.
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

namespace cv {
class ORB;
}

namespace viqu::slam {

struct OrbExtractorOptions {
  int num_features = 1200;     // target over all levels
  double scale_factor = 1.2;   // between pyramid levels
  int num_levels = 8;
  int fast_threshold = 20;     // initial FAST threshold (grey levels)
  int fast_threshold_min = 7;  // retry threshold for cells that found nothing
  int cell_px = 32;            // grid cell size at each level (px)
  bool level_pixel_centres = false;  // a coarse level's keypoint at its pixel's place in the image
                                     // (pyramid_level.h) rather than at x * scale^l
};

// No corners this close to a level's border (px): the rotated BRIEF patch must fit.
inline constexpr int kOrbEdgePx = 19;

// Why a width x height image cannot go through a pyramid of `num_levels` levels at
// `scale_factor` (its coarsest level is smaller than a FAST corner test), or "" when it can. Checked before a run starts: OpenCV asserts on an empty level.
std::string PyramidProblem(double scale_factor, int num_levels, int width, int height);

class OrbExtractor {
 public:
  explicit OrbExtractor(const OrbExtractorOptions& opt = {});

  // Features of an 8-bit grey image. Keypoints are in level-0 pixel coordinates with `octave`
  // set to the pyramid level and `angle` in degrees; descriptors are CV_8U, 32 bytes a row.
  // Pixels where `mask` (CV_8U, optional) is 0 get no features.
  void Extract(const cv::Mat& grey, const cv::Mat& mask, std::vector<cv::KeyPoint>* keypoints,
               cv::Mat* descriptors) const;

  const OrbExtractorOptions& options() const { return opt_; }
  double ScaleOfLevel(int level) const { return scales_.at(level); }

 private:
  // Corners of one pyramid level, spread by the cell grid, at most `quota`, in level coordinates.
  std::vector<cv::KeyPoint> DetectLevel(const cv::Mat& img, const cv::Mat& mask, int quota) const;

  OrbExtractorOptions opt_;
  std::vector<double> scales_;        // scale of each level relative to level 0
  std::vector<int> quota_;            // features wanted per level
  std::vector<int> umax_;             // circular patch row half-widths for the orientation
  cv::Ptr<cv::ORB> brief_;            // rotated-BRIEF descriptor computer, same pyramid settings
};

}  // namespace viqu::slam

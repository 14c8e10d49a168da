#include "slam/features/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/features/pyramid_level.h"

namespace viqu::slam {
namespace {

constexpr int kPatchSize = 31;       // BRIEF patch (px)
constexpr int kHalfPatch = 15;
constexpr int kEdge = kOrbEdgePx;

// Orientation of a corner from the intensity centroid of the circular patch around it (deg).
float CentroidAngle(const cv::Mat& img, cv::Point2f pt, const std::vector<int>& umax) {
  const int cx = cvRound(pt.x), cy = cvRound(pt.y);
  double m01 = 0, m10 = 0;
  for (int v = -kHalfPatch; v <= kHalfPatch; ++v) {
    const uchar* row = img.ptr<uchar>(cy + v);
    const int d = umax[std::abs(v)];
    for (int u = -d; u <= d; ++u) {
      const double i = row[cx + u];
      m10 += u * i;
      m01 += v * i;
    }
  }
  float a = static_cast<float>(std::atan2(m01, m10) * 180.0 / CV_PI);
  return a < 0 ? a + 360.f : a;
}

}  // namespace

std::string PyramidProblem(double scale_factor, int num_levels, int width, int height) {
  const double coarsest = std::pow(scale_factor, num_levels - 1);
  const int w = cvRound(width / coarsest), h = cvRound(height / coarsest);
  // FAST's 7x7 circle: a smaller level has no pixel to test (OpenCV asserts on an empty one).
  // Levels smaller than 2 * kEdge + 1 are allowed: they find nothing inside the border, as the
  // coarse levels of small images do.
  constexpr int min_side = 7;
  if (std::min(w, h) >= min_side) return "";
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "orb.num_levels %d at orb.scale_factor %g shrinks the %dx%d image to %dx%d px at the coarsest level, "
                "below the %d px a corner test needs; use fewer levels or a smaller scale factor",
                num_levels, scale_factor, width, height, w, h, min_side);
  return buf;
}

OrbExtractor::OrbExtractor(const OrbExtractorOptions& opt)
    : opt_(opt),
      brief_(cv::ORB::create(opt.num_features, static_cast<float>(opt.scale_factor), opt.num_levels, kEdge, 0, 2,
                             cv::ORB::HARRIS_SCORE, kPatchSize, opt.fast_threshold)) {
  scales_.resize(opt_.num_levels);
  for (int l = 0; l < opt_.num_levels; ++l) scales_[l] = std::pow(opt_.scale_factor, l);
  // Geometric split of the features over the levels, proportional to each level's area share.
  const double f = 1.0 / opt_.scale_factor;
  double per_level = opt_.num_features * (1 - f) / (1 - std::pow(f, opt_.num_levels));
  int total = 0;
  quota_.resize(opt_.num_levels);
  for (int l = 0; l < opt_.num_levels - 1; ++l) {
    quota_[l] = static_cast<int>(std::lround(per_level));
    total += quota_[l];
    per_level *= f;
  }
  quota_.back() = std::max(opt_.num_features - total, 0);
  umax_.resize(kHalfPatch + 1);
  for (int v = 0; v <= kHalfPatch; ++v) {
    umax_[v] = static_cast<int>(std::floor(std::sqrt(kHalfPatch * kHalfPatch + 0.5 * 2 - v * v)));
  }
}

std::vector<cv::KeyPoint> OrbExtractor::DetectLevel(const cv::Mat& img, const cv::Mat& mask, int quota) const {
  const int x0 = kEdge, y0 = kEdge, x1 = img.cols - kEdge, y1 = img.rows - kEdge;
  if (x1 <= x0 || y1 <= y0 || quota <= 0) return {};
  const int nx = std::max(1, (x1 - x0) / opt_.cell_px), ny = std::max(1, (y1 - y0) / opt_.cell_px);
  const double wx = double(x1 - x0) / nx, wy = double(y1 - y0) / ny;
  std::vector<std::vector<cv::KeyPoint>> cells(nx * ny);
  for (int cy = 0; cy < ny; ++cy) {
    for (int cx = 0; cx < nx; ++cx) {
      // A 3 px margin lets FAST (radius 3) test corners up to the cell's own border.
      const int ax = static_cast<int>(x0 + cx * wx), ay = static_cast<int>(y0 + cy * wy);
      const int bx = static_cast<int>(x0 + (cx + 1) * wx), by = static_cast<int>(y0 + (cy + 1) * wy);
      const cv::Rect roi(ax - 3, ay - 3, bx - ax + 6, by - ay + 6);
      std::vector<cv::KeyPoint> found;
      cv::FAST(img(roi), found, opt_.fast_threshold, true);
      if (found.empty()) cv::FAST(img(roi), found, opt_.fast_threshold_min, true);
      auto& cell = cells[cy * nx + cx];
      for (cv::KeyPoint& k : found) {
        k.pt.x += roi.x;
        k.pt.y += roi.y;
        if (k.pt.x < ax || k.pt.x >= bx || k.pt.y < ay || k.pt.y >= by) continue;
        if (!mask.empty() && !mask.at<uchar>(cvRound(k.pt.y), cvRound(k.pt.x))) continue;
        cell.push_back(k);
      }
      std::sort(cell.begin(), cell.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
        return a.response > b.response;
      });
    }
  }
  // Round-robin over the cells, best corner first, so every textured cell is represented.
  std::vector<cv::KeyPoint> out;
  for (size_t rank = 0; static_cast<int>(out.size()) < quota; ++rank) {
    bool any = false;
    for (const auto& cell : cells) {
      if (rank < cell.size()) {
        out.push_back(cell[rank]);
        any = true;
        if (static_cast<int>(out.size()) == quota) break;
      }
    }
    if (!any) break;
  }
  return out;
}

void OrbExtractor::Extract(const cv::Mat& grey, const cv::Mat& mask, std::vector<cv::KeyPoint>* keypoints,
                           cv::Mat* descriptors) const {
  CV_Assert(grey.type() == CV_8UC1);
  keypoints->clear();
  cv::Mat level_img = grey, level_mask = mask;
  std::vector<PyramidLevel> levels;
  for (int l = 0; l < opt_.num_levels; ++l) {
    levels.emplace_back(grey.size(), scales_[l], opt_.level_pixel_centres);
    if (l > 0) {
      const cv::Size size = levels.back().size();
      cv::resize(grey, level_img, size, 0, 0, cv::INTER_LINEAR);
      if (!mask.empty()) cv::resize(mask, level_mask, size, 0, 0, cv::INTER_NEAREST);
    }
    for (cv::KeyPoint& k : DetectLevel(level_img, level_mask, quota_[l])) {
      k.angle = CentroidAngle(level_img, k.pt, umax_);
      k.octave = l;
      k.size = static_cast<float>(kPatchSize * scales_[l]);
      // OpenCV's descriptor pass finds a keypoint on its level at pt / scale: hand it that.
      k.pt *= static_cast<float>(scales_[l]);
      keypoints->push_back(k);
    }
  }
  // Descriptors: OpenCV's rotated BRIEF on its own pyramid with the same levels, for the
  // keypoints (and angles) chosen above.
  brief_->detectAndCompute(grey, cv::noArray(), *keypoints, *descriptors, true);
  // Then, with level_pixel_centres, each keypoint goes where its level pixel lies in the image
  // (pyramid_level.h); without, it stays at x * scale^l (ORB-SLAM's and OpenCV's convention).
  if (!opt_.level_pixel_centres) return;
  for (cv::KeyPoint& k : *keypoints) {
    if (k.octave <= 0) continue;
    const double s = scales_[static_cast<size_t>(k.octave)];
    k.pt = levels[static_cast<size_t>(k.octave)].ToImage(
        cv::Point2f(static_cast<float>(std::round(k.pt.x / s)), static_cast<float>(std::round(k.pt.y / s))));
  }
}

}  // namespace viqu::slam

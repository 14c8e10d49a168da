#include "slam/core/frame.h"

#include <algorithm>
#include <cmath>

#include "slam/core/map.h"

namespace viqu::slam {

void FrameFeatures::BuildGrid(int width, int height) {
  grid_cols = (width + kCellPx - 1) / kCellPx;
  grid_rows = (height + kCellPx - 1) / kCellPx;
  grid.assign(static_cast<size_t>(grid_cols) * grid_rows, {});
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const int cx = std::clamp(static_cast<int>(keypoints[i].pt.x / kCellPx), 0, grid_cols - 1);
    const int cy = std::clamp(static_cast<int>(keypoints[i].pt.y / kCellPx), 0, grid_rows - 1);
    grid[cy * grid_cols + cx].push_back(static_cast<int>(i));
  }
}

std::vector<int> FrameFeatures::InArea(double u, double v, double radius, int min_level, int max_level) const {
  std::vector<int> out;
  const int x0 = std::max(0, static_cast<int>(std::floor((u - radius) / kCellPx)));
  const int x1 = std::min(grid_cols - 1, static_cast<int>(std::floor((u + radius) / kCellPx)));
  const int y0 = std::max(0, static_cast<int>(std::floor((v - radius) / kCellPx)));
  const int y1 = std::min(grid_rows - 1, static_cast<int>(std::floor((v + radius) / kCellPx)));
  const double r2 = radius * radius;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      for (int i : grid[y * grid_cols + x]) {
        const cv::KeyPoint& kp = keypoints[i];
        if (min_level >= 0 && kp.octave < min_level) continue;
        if (max_level >= 0 && kp.octave > max_level) continue;
        const double du = kp.pt.x - u, dv = kp.pt.y - v;
        if (du * du + dv * dv <= r2) out.push_back(i);
      }
    }
  }
  return out;
}

int Frame::MatchedCount() const {
  int n = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i] && !outlier[i] && !points[i]->bad) ++n;
  }
  return n;
}

void Frame::ForgetOutliers() {
  for (size_t i = 0; i < points.size(); ++i) {
    if (outlier[i]) {
      points[i] = nullptr;
      outlier[i] = false;
    }
  }
}

}  // namespace viqu::slam

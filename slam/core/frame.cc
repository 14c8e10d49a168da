#include "slam/core/frame.h"

#include <algorithm>
#include <cmath>

#include "slam/core/map.h"

namespace viqu::slam {

std::vector<FeaturePoint> ToFeaturePoints(const std::vector<cv::KeyPoint>& keypoints) {
  std::vector<FeaturePoint> out;
  out.reserve(keypoints.size());
  for (const cv::KeyPoint& k : keypoints) out.emplace_back(k.pt, k.octave);
  return out;
}

void FrameFeatures::BuildGrid(int width, int height) {
  grid_cols = (width + kCellPx - 1) / kCellPx;
  grid_rows = (height + kCellPx - 1) / kCellPx;
  const size_t cells = static_cast<size_t>(grid_cols) * grid_rows;
  std::vector<int> cell_of(keypoints.size());
  grid_start.assign(cells + 1, 0);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const int cx = std::clamp(static_cast<int>(keypoints[i].pt.x / kCellPx), 0, grid_cols - 1);
    const int cy = std::clamp(static_cast<int>(keypoints[i].pt.y / kCellPx), 0, grid_rows - 1);
    cell_of[i] = cy * grid_cols + cx;
    ++grid_start[cell_of[i] + 1];
  }
  for (size_t c = 0; c < cells; ++c) grid_start[c + 1] += grid_start[c];
  // Counting sort: each cell's features in increasing index, as a list per cell would hold them.
  grid_index.resize(keypoints.size());
  std::vector<int> next(grid_start.begin(), grid_start.end() - 1);
  for (size_t i = 0; i < keypoints.size(); ++i) grid_index[next[cell_of[i]]++] = static_cast<int>(i);
}

std::vector<int> FrameFeatures::InArea(double u, double v, double radius, int min_level, int max_level) const {
  std::vector<int> out;
  InArea(u, v, radius, min_level, max_level, &out);
  return out;
}

void FrameFeatures::InArea(double u, double v, double radius, int min_level, int max_level, std::vector<int>* out) const {
  out->clear();
  const int x0 = std::max(0, static_cast<int>(std::floor((u - radius) / kCellPx)));
  const int x1 = std::min(grid_cols - 1, static_cast<int>(std::floor((u + radius) / kCellPx)));
  const int y0 = std::max(0, static_cast<int>(std::floor((v - radius) / kCellPx)));
  const int y1 = std::min(grid_rows - 1, static_cast<int>(std::floor((v + radius) / kCellPx)));
  const double r2 = radius * radius;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const int cell = y * grid_cols + x;
      for (int k = grid_start[cell]; k < grid_start[cell + 1]; ++k) {
        const int i = grid_index[k];
        const FeaturePoint& kp = keypoints[i];
        if (min_level >= 0 && kp.octave < min_level) continue;
        if (max_level >= 0 && kp.octave > max_level) continue;
        const double du = kp.pt.x - u, dv = kp.pt.y - v;
        if (du * du + dv * dv <= r2) out->push_back(i);
      }
    }
  }
}

void FrameFeatures::LabelObjects(const cv::Mat& instance_id) {
  object.assign(keypoints.size(), 0);
  if (instance_id.empty()) return;
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const int u = std::clamp(static_cast<int>(std::lround(keypoints[i].pt.x)), 0, instance_id.cols - 1);
    const int v = std::clamp(static_cast<int>(std::lround(keypoints[i].pt.y)), 0, instance_id.rows - 1);
    object[i] = instance_id.at<uint16_t>(v, u);
  }
}

std::shared_ptr<FrameFeatures> FrameFeatures::Subset(const std::vector<bool>& keep, int width, int height) const {
  auto f = std::make_shared<FrameFeatures>();
  f->level_sigma2 = level_sigma2;
  f->level_scale = level_scale;
  std::vector<int> rows;
  for (size_t i = 0; i < keypoints.size(); ++i) {
    if (!keep[i]) continue;
    rows.push_back(static_cast<int>(i));
    f->keypoints.push_back(keypoints[i]);
    f->u_right.push_back(u_right[i]);
    f->depth.push_back(depth[i]);
    f->object.push_back(object.empty() ? 0 : object[i]);
  }
  f->descriptors.create(static_cast<int>(rows.size()), descriptors.cols, descriptors.type());
  for (size_t r = 0; r < rows.size(); ++r) descriptors.row(rows[r]).copyTo(f->descriptors.row(static_cast<int>(r)));
  f->BuildGrid(width, height);
  return f;
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

#include "slam/eval/trajectory_error.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "common/errors.h"

namespace viqu::eval {

ErrorStats ComputeStats(std::vector<double> e) {
  ErrorStats s;
  s.count = e.size();
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  double sum = 0, sum_sq = 0;
  for (double x : e) {
    sum += x;
    sum_sq += x * x;
  }
  const double n = static_cast<double>(e.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  s.std = std::sqrt(std::max(0.0, sum_sq / n - s.mean * s.mean));  // population std, as numpy.std
  s.min = e.front();
  s.max = e.back();
  const size_t mid = e.size() / 2;
  s.median = e.size() % 2 ? e[mid] : 0.5 * (e[mid - 1] + e[mid]);
  return s;
}

Alignment UmeyamaAlign(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
                       bool with_scale) {
  if (from.size() != to.size() || from.size() < 3) {
    throw InputError("alignment needs at least 3 associated poses, got " + std::to_string(from.size()));
  }
  Eigen::Matrix3Xd src(3, from.size()), dst(3, to.size());
  for (size_t i = 0; i < from.size(); ++i) {
    src.col(static_cast<Eigen::Index>(i)) = from[i];
    dst.col(static_cast<Eigen::Index>(i)) = to[i];
  }
  // Umeyama (1991), as TUM's evaluate_ate.py aligns; Eigen's implementation keeps the rotation
  // proper (no reflection) and gives the scale only when asked.
  const Eigen::Matrix4d T = Eigen::umeyama(src, dst, with_scale);
  Alignment a;
  a.scale = with_scale ? T.block<3, 1>(0, 0).norm() : 1.0;
  a.R = T.block<3, 3>(0, 0) / a.scale;
  a.t = T.block<3, 1>(0, 3);
  return a;
}

AteResult ComputeAte(const Trajectory& est, const Trajectory& gt, bool with_scale, double max_diff_s) {
  const auto pairs = Associate(est, gt, max_diff_s);
  std::vector<Eigen::Vector3d> from, to;
  for (const auto& [i, j] : pairs) {
    from.push_back(est[i].p_w_x);
    to.push_back(gt[j].p_w_x);
  }
  AteResult r;
  r.pairs = pairs.size();
  r.alignment = UmeyamaAlign(from, to, with_scale);
  std::vector<double> errors;
  for (size_t k = 0; k < from.size(); ++k) {
    errors.push_back((to[k] - (r.alignment.scale * r.alignment.R * from[k] + r.alignment.t)).norm());
  }
  r.ate = ComputeStats(std::move(errors));
  return r;
}

ErrorStats ComputeRpe(const Trajectory& est, const Trajectory& gt, int delta_frames, double delta_m,
                      double max_diff_s) {
  const auto pairs = Associate(est, gt, max_diff_s);
  std::vector<Eigen::Isometry3d> P, G;
  for (const auto& [i, j] : pairs) {
    P.push_back(ToIsometry(est[i]));
    G.push_back(ToIsometry(gt[j]));
  }
  // Distance travelled along the ground truth up to each pair (m).
  std::vector<double> along(G.size(), 0.0);
  for (size_t k = 1; k < G.size(); ++k) along[k] = along[k - 1] + (G[k].translation() - G[k - 1].translation()).norm();
  std::vector<double> errors;
  for (size_t k = 0; k < G.size(); ++k) {
    size_t l = k;
    if (delta_m > 0) {
      l = static_cast<size_t>(std::lower_bound(along.begin() + k, along.end(), along[k] + delta_m) - along.begin());
    } else {
      l = k + static_cast<size_t>(std::max(delta_frames, 1));
    }
    if (l >= G.size()) break;
    const Eigen::Isometry3d E = (G[k].inverse() * G[l]).inverse() * (P[k].inverse() * P[l]);
    errors.push_back(E.translation().norm());
  }
  return ComputeStats(std::move(errors));
}

}  // namespace viqu::eval

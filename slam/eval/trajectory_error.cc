#include "slam/eval/trajectory_error.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

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
  const double n = static_cast<double>(from.size());
  Eigen::Vector3d mu_from = Eigen::Vector3d::Zero(), mu_to = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    mu_from += from[i];
    mu_to += to[i];
  }
  mu_from /= n;
  mu_to /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double var_from = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    cov += (to[i] - mu_to) * (from[i] - mu_from).transpose();
    var_from += (from[i] - mu_from).squaredNorm();
  }
  cov /= n;
  var_from /= n;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;  // no reflection
  Alignment a;
  a.R = svd.matrixU() * S * svd.matrixV().transpose();
  a.scale = with_scale && var_from > 0 ? (svd.singularValues().asDiagonal() * S).trace() / var_from : 1.0;
  a.t = mu_to - a.scale * a.R * mu_from;
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

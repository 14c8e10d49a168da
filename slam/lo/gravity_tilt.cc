#include "slam/lo/gravity_tilt.h"

#include <cmath>

namespace viqu::lo {

void GravityTilt::Reset() {
  q_g_b_.setIdentity();
  last_gyro_.setZero();
  sum_.setZero();
  count_ = 0;
  last_t_ns_.reset();
  entries_.clear();
}

void GravityTilt::Add(int64_t t_ns, const Eigen::Vector3d& gyro_b, const Eigen::Vector3d& accel_b) {
  if (last_t_ns_ && t_ns > *last_t_ns_) {
    const Eigen::Vector3d turn = 0.5 * (last_gyro_ + gyro_b) * ((t_ns - *last_t_ns_) * 1e-9);
    const double angle = turn.norm();
    if (angle > 0) q_g_b_ = (q_g_b_ * Eigen::Quaterniond(Eigen::AngleAxisd(angle, turn / angle))).normalized();
  }
  last_t_ns_ = t_ns;
  last_gyro_ = gyro_b;
  sum_ += q_g_b_ * accel_b;
  ++count_;
  entries_.push_back(Entry{t_ns, sum_, count_});
  // Keep as the front the newest entry at least one window old, so that the difference of the
  // sums spans the whole window.
  while (entries_.size() > 2 && entries_[1].t_ns <= t_ns - window_ns_) entries_.pop_front();
}

std::optional<Eigen::Vector3d> GravityTilt::MeanForceBody() const {
  if (entries_.size() < 2 || entries_.front().t_ns > entries_.back().t_ns - window_ns_) return std::nullopt;
  const Entry& a = entries_.front();
  const Entry& b = entries_.back();
  const Eigen::Vector3d mean_g = (b.sum - a.sum) / static_cast<double>(b.count - a.count);
  return q_g_b_.conjugate() * mean_g;
}

std::optional<Eigen::Vector3d> GravityTilt::LevellingOf(const Eigen::Matrix3d& R_w_b) const {
  const std::optional<Eigen::Vector3d> f_b = MeanForceBody();
  if (!f_b || f_b->norm() == 0) return std::nullopt;
  const Eigen::Vector3d up = (R_w_b * *f_b).normalized();
  // The rotation taking `up` onto the world's z: about up x z by the angle between them.
  const Eigen::Vector3d axis = up.cross(Eigen::Vector3d::UnitZ());
  const double s = axis.norm();
  if (s == 0) return Eigen::Vector3d::Zero();
  return axis / s * std::atan2(s, up.z());
}

}  // namespace viqu::lo

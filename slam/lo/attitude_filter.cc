#include "slam/lo/attitude_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace viqu::lo {
namespace {

// Rotation by the rotation vector w (rad) as a unit quaternion.
Eigen::Quaterniond Exp(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

}  // namespace

void AttitudeFilter::Reset(int64_t t_ns, const Eigen::Quaterniond& q_w_b, const Eigen::Vector3d& gyro_bias) {
  q_w_b_ = q_w_b.normalized();
  bias_ = gyro_bias;
  last_t_ns_ = t_ns;
  last_gyro_ = bias_;
  have_rate_ = false;  // no rotation before the first sample
  correction_.setZero();
  corrected_ = false;
  force_w_.reset();
}

void AttitudeFilter::SetOrientation(const Eigen::Quaterniond& q_w_b) {
  const Eigen::Quaterniond q = q_w_b.normalized();
  if (force_w_) force_w_ = q * (q_w_b_.conjugate() * *force_w_);
  q_w_b_ = q;
}

Eigen::Quaterniond AttitudeFilter::OrientationAt(int64_t t_ns) const {
  if (!last_t_ns_) return q_w_b_;
  return (q_w_b_ * Exp(angular_velocity() * ((t_ns - *last_t_ns_) * 1e-9))).normalized();
}

void AttitudeFilter::Add(const ImuSample& s) {
  if (last_t_ns_ && s.t_ns < *last_t_ns_) throw std::invalid_argument("IMU time went backwards");
  const double dt = last_t_ns_ ? (s.t_ns - *last_t_ns_) * 1e-9 : 0.0;
  // Instant readings: integrate the mean of the interval's two rates (bias-corrected, plus the
  // last correction): holding the earlier rate instead would lag the orientation by half a sample
  // interval, which on the trot's jolts turned each camera frame's prior by 0.2 deg instead of
  // 0.08 deg. An interval-mean reading is the interval's own rate.
  if (dt > 0 && have_rate_) {
    const Eigen::Vector3d rate = opt_.interval_mean ? s.gyro_i : 0.5 * (last_gyro_ + s.gyro_i);
    q_w_b_ = (q_w_b_ * Exp((rate - bias_ + correction_) * dt)).normalized();
  }
  last_t_ns_ = s.t_ns;
  last_gyro_ = s.gyro_i;
  have_rate_ = true;

  // Gravity correction: the accelerometer's direction is "up" in the body frame when the trunk
  // is not accelerating; the cross product with the predicted up gives the tilt error.
  correction_.setZero();
  Eigen::Vector3d force = s.accel_i;  // body frame
  if (opt_.accel_average_s > 0) {
    const Eigen::Vector3d f_w = q_w_b_ * s.accel_i;
    if (!force_w_) force_w_ = f_w;
    *force_w_ += std::min(1.0, dt / opt_.accel_average_s) * (f_w - *force_w_);
    force = q_w_b_.conjugate() * *force_w_;
  }
  const double norm = force.norm();
  corrected_ = !hold_ && std::abs(norm - opt_.gravity_mps2) <= opt_.gravity_gate_mps2 && norm > 0;
  if (!corrected_) return;
  const Eigen::Vector3d up_measured = force / norm;
  const Eigen::Vector3d up_predicted = q_w_b_.conjugate() * Eigen::Vector3d::UnitZ();
  // A body rotation rate along `error` turns the predicted up towards the measured one.
  const Eigen::Vector3d error = up_measured.cross(up_predicted);
  correction_ = opt_.attitude_gain * error;
  bias_ -= opt_.gyro_bias_gain * error * dt;
}

}  // namespace viqu::lo

#pragma once
// Attitude of the trunk from the IMU alone: a complementary filter on SO(3) in Mahony's form.
// The gyro is integrated; the accelerometer, when it reads about g, says where "up" is and pulls
// roll and pitch towards it proportionally (attitude_gain) and, through an integral term
// (gyro_bias_gain), estimates the gyro bias on the axes that gravity observes. Yaw and the gyro
// bias about the vertical are not observable this way: they drift, at the gyro bias rate.
#include <cstdint>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "slam/measurements/imu_sample.h"

namespace viqu::lo {

struct AttitudeFilterOptions {
  double attitude_gain = 0.5;      // proportional gain of the gravity correction (1/s)
  double gyro_bias_gain = 0.005;   // integral gain: bias estimate rate per rad of tilt error (1/s^2)
  double gravity_gate_mps2 = 1.5;  // skip the correction when | |accel| - g | exceeds this (m/s^2)
  double gravity_mps2 = 9.81;      // local gravity (m/s^2); a constant of the world, not tuned
  // The accelerometer's "up" is the specific force averaged in the world frame over this time
  // constant (s), not each sample's own direction: averaging the vector cancels the trunk's
  // zero-mean accelerations, while the mean of each sample's normalised direction is biased by
  // their correlations (on the trot, fore-aft with vertical). 0: each sample on its own.
  double accel_average_s = 0.0;
  // A reading's gyro is the mean rate over the interval since the previous reading (true), or the
  // rate at its time (false: the interval takes the mean of its two ends' rates).
  bool interval_mean = false;
};

class AttitudeFilter {
 public:
  explicit AttitudeFilter(const AttitudeFilterOptions& opt) : opt_(opt) {}

  // Starts at a known orientation (body to world) at time t_ns with a gyro bias estimate.
  void Reset(int64_t t_ns, const Eigen::Quaterniond& q_w_b,
             const Eigen::Vector3d& gyro_bias = Eigen::Vector3d::Zero());

  // Integrates the gyro from the previous sample's time to this one (the mean of the two samples'
  // rates: exact for a rate that changes linearly) and applies the gravity correction of this
  // sample. The first sample after Reset only stores the rates. Throws std::invalid_argument
  // for time going backwards.
  void Add(const ImuSample& s);

  // Replaces the orientation (a correction from elsewhere, e.g. vision); the bias estimate stays,
  // and the averaged specific force turns with the correction (it is the same force, seen from
  // the corrected orientation).
  void SetOrientation(const Eigen::Quaterniond& q_w_b);

  // Adds db (rad/s, body frame) to the gyro bias estimate: a bias found from elsewhere (the
  // stance feet observe the rate about the vertical, which gravity does not).
  void AddGyroBias(const Eigen::Vector3d& db) { bias_ += db; }

  // While held, Add integrates the gyro only: no gravity correction and no bias update (the
  // orientation comes from elsewhere, e.g. vision every frame, and the per-sample gravity
  // direction, which leans with the gait, would only pull it off and wind the bias up).
  void HoldGravity(bool hold) { hold_ = hold; }

  const Eigen::Quaterniond& q_w_b() const { return q_w_b_; }
  // The orientation at t_ns, extrapolated from the last sample with its bias-corrected rate.
  Eigen::Quaterniond OrientationAt(int64_t t_ns) const;
  bool started() const { return last_t_ns_.has_value(); }  // Reset has been called
  const Eigen::Vector3d& gyro_bias() const { return bias_; }           // (rad/s)
  Eigen::Vector3d angular_velocity() const { return last_gyro_ - bias_; }  // bias-corrected (rad/s, body)
  bool corrected_last() const { return corrected_; }  // the last sample passed the gravity gate

 private:
  AttitudeFilterOptions opt_;
  Eigen::Quaterniond q_w_b_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_gyro_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d correction_ = Eigen::Vector3d::Zero();  // proportional term of the last sample (rad/s)
  std::optional<Eigen::Vector3d> force_w_;  // specific force averaged in the world frame (m/s^2)
  std::optional<int64_t> last_t_ns_;
  bool have_rate_ = false;  // a sample has come since Reset
  bool corrected_ = false;
  bool hold_ = false;
};

}  // namespace viqu::lo

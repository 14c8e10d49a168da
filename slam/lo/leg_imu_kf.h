#pragma once
// The linear Kalman filter of legged state estimation (paper eq. 5; the form of MIT Cheetah 3's
// estimator). State, all in the world frame: body position p (3), body velocity v (3) and the
// four foot positions f_1..f_4 (12), 18 in all.
//   Predict over dt with the world acceleration a (the IMU's specific force rotated to the world,
//   minus gravity):  p += v dt + a dt^2 / 2,  v += a dt,  feet move only as they roll; process noise from the
//   acceleration input (on p and v) and a random walk per foot (small in stance, large in swing,
//   so that a lifted foot follows the kinematics freely).
//   Update per foot with the kinematics rotated to the world: the foot-minus-body position
//   z = f_i - p, and for a foot that stands still, the body velocity v = -R (J qd + w x r).
// The orientation R is an input (from the attitude filter), which keeps the filter linear.
#include <array>

#include <Eigen/Core>

#include "slam/measurements/joint_state.h"

namespace viqu::lo {

constexpr int kKfStates = 6 + 3 * kNumLegs;  // 18

class LegImuKf {
 public:
  using Vec = Eigen::Matrix<double, kKfStates, 1>;
  using Mat = Eigen::Matrix<double, kKfStates, kKfStates>;

  // Sets the state and a diagonal covariance: position_std (m), velocity_std (m/s), foot_std (m).
  void Reset(const Eigen::Vector3d& p, const Eigen::Vector3d& v, const std::array<Eigen::Vector3d, kNumLegs>& feet,
             double position_std, double velocity_std, double foot_std);

  // Propagates over dt_s (s) with the world acceleration a_w (m/s^2, gravity removed).
  // accel_noise: white acceleration noise (m/s^2/sqrt(Hz)); foot_noise[i]: random walk of foot i
  // (m/sqrt(s)); foot_vel[i]: known motion of foot i's centre (m/s, world), for a foot that rolls
  // over the ground. dt_s <= 0 does nothing.
  void Predict(double dt_s, const Eigen::Vector3d& a_w, double accel_noise,
               const std::array<double, kNumLegs>& foot_noise,
               const std::array<Eigen::Vector3d, kNumLegs>& foot_vel);
  // The same with feet that do not move.
  void Predict(double dt_s, const Eigen::Vector3d& a_w, double accel_noise,
               const std::array<double, kNumLegs>& foot_noise);

  // Foot i's position relative to the body in the world frame, rel_w = f_i - p, with an isotropic
  // standard deviation (m).
  void UpdateFootPosition(int leg, const Eigen::Vector3d& rel_w, double std_m);
  // The same with a standard deviation per world axis (m).
  void UpdateFootPosition(int leg, const Eigen::Vector3d& rel_w, const Eigen::Vector3d& std_m);

  // The body velocity measured through a standing foot (m/s) with an isotropic standard deviation.
  void UpdateVelocity(const Eigen::Vector3d& v_w, double std_mps);
  // The same with a standard deviation per world axis (m/s).
  void UpdateVelocity(const Eigen::Vector3d& v_w, const Eigen::Vector3d& std_mps);

  // Squared Mahalanobis distance y^T (P_vv + std^2 I)^-1 y of a velocity innovation y (a measured
  // velocity minus the filter's, before any update with it) of isotropic standard deviation std.
  double VelocityInnovationMahalanobis2(const Eigen::Vector3d& y, double std_mps) const;

  Eigen::Vector3d position() const { return x_.segment<3>(0); }
  Eigen::Vector3d velocity() const { return x_.segment<3>(3); }
  Eigen::Vector3d foot(int leg) const { return x_.segment<3>(6 + 3 * leg); }
  const Mat& covariance() const { return P_; }

  // Shifts the whole state (body and feet) by dp (m): a correction of position from elsewhere
  // that keeps the feet consistent with the body.
  void Translate(const Eigen::Vector3d& dp);

 private:
  Vec x_ = Vec::Zero();
  Mat P_ = Mat::Identity();
};

}  // namespace viqu::lo

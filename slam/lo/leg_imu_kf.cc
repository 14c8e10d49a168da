#include "slam/lo/leg_imu_kf.h"

#include <Eigen/Cholesky>

namespace viqu::lo {

void LegImuKf::Reset(const Eigen::Vector3d& p, const Eigen::Vector3d& v, const std::array<Eigen::Vector3d, kNumLegs>& feet,
                     double position_std, double velocity_std, double foot_std) {
  x_.segment<3>(0) = p;
  x_.segment<3>(3) = v;
  for (int i = 0; i < kNumLegs; ++i) x_.segment<3>(6 + 3 * i) = feet[i];
  P_.setZero();
  P_.diagonal().segment<3>(0).setConstant(position_std * position_std);
  P_.diagonal().segment<3>(3).setConstant(velocity_std * velocity_std);
  P_.diagonal().segment<3 * kNumLegs>(6).setConstant(foot_std * foot_std);
}

void LegImuKf::Predict(double dt, const Eigen::Vector3d& a_w, double accel_noise,
                       const std::array<double, kNumLegs>& foot_noise,
                       const std::array<Eigen::Vector3d, kNumLegs>& foot_vel) {
  if (dt <= 0) return;
  x_.segment<3>(0) += x_.segment<3>(3) * dt + 0.5 * dt * dt * a_w;
  x_.segment<3>(3) += a_w * dt;
  for (int i = 0; i < kNumLegs; ++i) x_.segment<3>(6 + 3 * i) += foot_vel[i] * dt;
  // P = F P F^T with F = [I dt I; 0 I] on (p, v) and identity on the feet, written out by blocks.
  // Columns first (P F^T), then rows (F (P F^T)).
  P_.block<kKfStates, 3>(0, 0) += dt * P_.block<kKfStates, 3>(0, 3);
  P_.block<3, kKfStates>(0, 0) += dt * P_.block<3, kKfStates>(3, 0);
  // Q: white acceleration noise q = accel_noise^2 (m^2/s^3) integrated over dt:
  // [dt^3/3 dt^2/2; dt^2/2 dt] q per axis; a foot's random walk adds noise^2 dt.
  const double q = accel_noise * accel_noise;
  for (int k = 0; k < 3; ++k) {
    P_(k, k) += q * dt * dt * dt / 3;
    P_(k, 3 + k) += q * dt * dt / 2;
    P_(3 + k, k) += q * dt * dt / 2;
    P_(3 + k, 3 + k) += q * dt;
  }
  for (int i = 0; i < kNumLegs; ++i) {
    const double w = foot_noise[i] * foot_noise[i] * dt;
    for (int k = 0; k < 3; ++k) P_(6 + 3 * i + k, 6 + 3 * i + k) += w;
  }
}

void LegImuKf::Predict(double dt, const Eigen::Vector3d& a_w, double accel_noise,
                       const std::array<double, kNumLegs>& foot_noise) {
  std::array<Eigen::Vector3d, kNumLegs> still;
  still.fill(Eigen::Vector3d::Zero());
  Predict(dt, a_w, accel_noise, foot_noise, still);
}

void LegImuKf::UpdateFootPosition(int leg, const Eigen::Vector3d& rel_w, double std_m) {
  UpdateFootPosition(leg, rel_w, Eigen::Vector3d::Constant(std_m));
}

void LegImuKf::UpdateFootPosition(int leg, const Eigen::Vector3d& rel_w, const Eigen::Vector3d& std_m) {
  const int f = 6 + 3 * leg;
  // H = [-I 0 ... I(at foot) ...]; H P and H P H^T by blocks.
  const Eigen::Matrix<double, 3, kKfStates> HP = P_.block<3, kKfStates>(f, 0) - P_.block<3, kKfStates>(0, 0);
  Eigen::Matrix3d S = HP.block<3, 3>(0, f) - HP.block<3, 3>(0, 0);
  S.diagonal() += std_m.cwiseAbs2();
  const Eigen::Vector3d y = rel_w - (x_.segment<3>(f) - x_.segment<3>(0));
  const Eigen::LLT<Eigen::Matrix3d> llt(S);
  const Eigen::Matrix<double, kKfStates, 3> K = llt.solve(HP).transpose();  // P H^T S^-1 (S symmetric)
  x_ += K * y;
  P_ -= K * HP;
  P_ = 0.5 * (P_ + P_.transpose()).eval();
}

void LegImuKf::UpdateVelocity(const Eigen::Vector3d& v_w, double std_mps) {
  UpdateVelocity(v_w, Eigen::Vector3d::Constant(std_mps));
}

void LegImuKf::UpdateVelocity(const Eigen::Vector3d& v_w, const Eigen::Vector3d& std_mps) {
  const Eigen::Matrix<double, 3, kKfStates> HP = P_.block<3, kKfStates>(3, 0);
  Eigen::Matrix3d S = HP.block<3, 3>(0, 3);
  S.diagonal() += std_mps.cwiseAbs2();
  const Eigen::Vector3d y = v_w - x_.segment<3>(3);
  const Eigen::LLT<Eigen::Matrix3d> llt(S);
  const Eigen::Matrix<double, kKfStates, 3> K = llt.solve(HP).transpose();
  x_ += K * y;
  P_ -= K * HP;
  P_ = 0.5 * (P_ + P_.transpose()).eval();
}

double LegImuKf::VelocityInnovationMahalanobis2(const Eigen::Vector3d& y, double std_mps) const {
  Eigen::Matrix3d S = P_.block<3, 3>(3, 3);
  S.diagonal().array() += std_mps * std_mps;
  return y.dot(S.llt().solve(y));
}

void LegImuKf::Translate(const Eigen::Vector3d& dp) {
  x_.segment<3>(0) += dp;
  for (int i = 0; i < kNumLegs; ++i) x_.segment<3>(6 + 3 * i) += dp;
}

}  // namespace viqu::lo

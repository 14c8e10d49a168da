#pragma once
// The reprojection residual of one observation and its Jacobians for a left perturbation of the
// pose, the Huber kernel, and the pose update: what the pose-only optimiser and local BA's
// solver share (slam/core/pose_optimizer.cc, ba_solver.cc). Internal to slam/core.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "slam/core/camera.h"

namespace viqu::slam {

// The residual of one observation at pose T and point P: pixels of the level (rows u, v and, for
// stereo, the right column; a monocular third row is 0). The depth is clamped at 1e-4 m as the
// Ceres residual did. Optionally the Jacobians for the left perturbation of T
// (T <- [exp(omega) | nu] T: dp = -[p]x omega + nu) and for P.
struct Residual {
  Eigen::Vector3d r;
  Eigen::Matrix<double, 3, 6> J_pose;
  Eigen::Matrix3d J_point;
};

// `u`, `v`: the measured pixel, `ur`: the right image's column (< 0: monocular), `w`: 1 / level scale,
// `wr`: a further scale of the right-column row (StereoCamera::RightScale).
inline void EvaluateReprojection(const StereoCamera& cam, double u_obs, double v_obs, double ur, double w,
                                 const Eigen::Isometry3d& T, const Eigen::Vector3d& P, bool jacobians,
                                 Residual* out, double wr) {
  const Eigen::Vector3d p = T * P;
  const bool clamped = p.z() < 1e-4;
  const double z = clamped ? 1e-4 : p.z();
  const double inv_z = 1.0 / z;
  const double u = cam.fx * p.x() * inv_z + cam.cx;
  const double v = cam.fy * p.y() * inv_z + cam.cy;
  const bool stereo = ur >= 0;
  out->r << (u - u_obs) * w, (v - v_obs) * w, stereo ? (u - cam.bf * inv_z - ur) * w * wr : 0.0;
  if (!jacobians) return;
  Eigen::Matrix3d Jp = Eigen::Matrix3d::Zero();  // d r / d p
  const double inv_z2 = inv_z * inv_z;
  Jp(0, 0) = cam.fx * inv_z;
  Jp(0, 2) = -cam.fx * p.x() * inv_z2;
  Jp(1, 1) = cam.fy * inv_z;
  Jp(1, 2) = -cam.fy * p.y() * inv_z2;
  if (stereo) {
    Jp(2, 0) = cam.fx * inv_z;
    Jp(2, 2) = (cam.bf - cam.fx * p.x()) * inv_z2;
    Jp.row(2) *= wr;
  }
  if (clamped) Jp.col(2).setZero();  // the clamp makes the residual flat in z there
  Jp *= w;
  Eigen::Matrix3d skew;
  skew << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
  out->J_pose.leftCols<3>() = -Jp * skew;
  out->J_pose.rightCols<3>() = Jp;
  out->J_point = Jp * T.linear();
}

// Huber cost of a squared residual norm `s` with width `a`, and the IRLS weight rho'(s).
inline double HuberCost(double s, double a, double* weight) {
  if (s <= a * a) {
    if (weight) *weight = 1.0;
    return s;
  }
  const double norm = std::sqrt(s);
  if (weight) *weight = a / norm;
  return 2 * a * norm - a * a;
}

// T moved by the left perturbation d = (omega, nu): [exp(omega) | nu] T, re-orthonormalised.
inline Eigen::Isometry3d PerturbLeft(const Eigen::Isometry3d& T, const Eigen::Matrix<double, 6, 1>& d) {
  const Eigen::Vector3d omega = d.head<3>();
  const double angle = omega.norm();
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  if (angle > 1e-15) D.linear() = Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
  D.translation() = d.tail<3>();
  Eigen::Isometry3d out = D * T;
  out.linear() = Eigen::Quaterniond(out.rotation()).normalized().toRotationMatrix();
  return out;
}

}  // namespace viqu::slam

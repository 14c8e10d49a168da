#pragma once
// Ceres residuals of one observation of a map point: what pose-only optimisation and local BA
// minimised through Ceres before they were written out (slam/core/pose_optimizer.cc,
// ba_solver.cc), kept as the independent reference of their tests. The pose block is T_c_w as
// [angle-axis (3), translation (3)];
// residuals are pixel errors divided by the feature's level scale (the information of an
// observation at level l is 1 / scale^(2 l), as ORB-SLAM weights them).
#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <Eigen/Geometry>

#include "slam/core/camera.h"

namespace viqu::slam {

// Monocular observation (u, v), or stereo (u, v, u_right) when `stereo`.
struct ReprojectionCost {
  ReprojectionCost(const StereoCamera& cam, double u, double v, double ur, double inv_sigma)
      : fx(cam.fx), fy(cam.fy), cx(cam.cx), cy(cam.cy), bf(cam.bf), u(u), v(v), ur(ur), w(inv_sigma) {}

  template <typename T>
  bool Project(const T* pose, const T* p_w, T* uv, T* z, T* x) const {
    T p[3];
    ceres::AngleAxisRotatePoint(pose, p_w, p);
    p[0] += pose[3];
    p[1] += pose[4];
    p[2] += pose[5];
    if (p[2] < T(1e-4)) p[2] = T(1e-4);
    const T inv_z = T(1) / p[2];
    uv[0] = T(fx) * p[0] * inv_z + T(cx);
    uv[1] = T(fy) * p[1] * inv_z + T(cy);
    *z = p[2];
    *x = p[0];
    return true;
  }

  template <typename T>
  bool operator()(const T* pose, const T* p_w, T* r) const {
    T uv[2], z, x;
    Project(pose, p_w, uv, &z, &x);
    r[0] = (uv[0] - T(u)) * T(w);
    r[1] = (uv[1] - T(v)) * T(w);
    return true;
  }

  double fx, fy, cx, cy, bf, u, v, ur, w;
};

struct StereoReprojectionCost : ReprojectionCost {
  using ReprojectionCost::ReprojectionCost;
  template <typename T>
  bool operator()(const T* pose, const T* p_w, T* r) const {
    T uv[2], z, x;
    Project(pose, p_w, uv, &z, &x);
    r[0] = (uv[0] - T(u)) * T(w);
    r[1] = (uv[1] - T(v)) * T(w);
    r[2] = (uv[0] - T(bf) / z - T(ur)) * T(w);
    return true;
  }
};

// The same with the point held constant (pose-only optimisation).
template <class Cost>
struct FixedPointCost {
  FixedPointCost(const Cost& c, const Eigen::Vector3d& p) : cost(c), p_w{p.x(), p.y(), p.z()} {}
  template <typename T>
  bool operator()(const T* pose, T* r) const {
    const T p[3] = {T(p_w[0]), T(p_w[1]), T(p_w[2])};
    return cost(pose, p, r);
  }
  Cost cost;
  double p_w[3];
};

inline void PoseToParams(const Eigen::Isometry3d& T, double* q) {
  Eigen::AngleAxisd aa(T.rotation());
  const Eigen::Vector3d v = aa.angle() * aa.axis();
  q[0] = v.x(); q[1] = v.y(); q[2] = v.z();
  q[3] = T.translation().x(); q[4] = T.translation().y(); q[5] = T.translation().z();
}

inline Eigen::Isometry3d ParamsToPose(const double* q) {
  const Eigen::Vector3d v(q[0], q[1], q[2]);
  const double angle = v.norm();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (angle > 1e-12) T.linear() = Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
  T.translation() = Eigen::Vector3d(q[3], q[4], q[5]);
  return T;
}

}  // namespace viqu::slam

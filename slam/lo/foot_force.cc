#include "slam/lo/foot_force.h"

#include <cmath>

namespace viqu::lo {

FootForceEstimator::FootForceEstimator(const kin::LegKinematics& kin, const FootForceModel& model,
                                       ForceAlignment alignment)
    : kin_(kin), model_(model), alignment_(alignment) {}

FootForces FootForceEstimator::Update(const JointState& js, const Eigen::Vector3d& g_trunk) {
  FootForces out;
  out.t_ns = js.t_ns;
  std::array<double, kNumJoints> qdd{};
  const bool had_last = have_last_ && js.t_ns > last_.t_ns;
  if (had_last) {
    const double dt = 1e-9 * static_cast<double>(js.t_ns - last_.t_ns);
    for (int j = 0; j < kNumJoints; ++j) qdd[j] = (js.velocity_rad_s[j] - last_.velocity_rad_s[j]) / dt;
  }
  // The reading the estimate is about: the newest, or (centred) the previous one with the mean
  // of the two velocities.
  JointState at = js;
  if (alignment_ == ForceAlignment::kCentred) {
    if (!had_last) {
      have_last_ = true;
      last_ = js;
      return out;
    }
    at = last_;
    for (int j = 0; j < kNumJoints; ++j) at.velocity_rad_s[j] = 0.5 * (js.velocity_rad_s[j] + last_.velocity_rad_s[j]);
    out.t_ns = last_.t_ns;
  }
  have_last_ = true;
  last_ = js;
  if (!at.has_torque) return out;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg leg = static_cast<Leg>(i);
    const int j1 = 2 * i, j2 = 2 * i + 1;
    const double q1 = at.position_rad[j1], q2 = at.position_rad[j2];
    const Eigen::Matrix<double, 3, 2> J = kin_.FootJacobian(leg, q1, q2);
    Eigen::Matrix2d Js;  // rows x and z of the trunk frame
    Js.row(0) = J.row(0);
    Js.row(1) = J.row(2);
    if (!(std::abs(Js.determinant()) >= model_.min_jacobian_det_m2)) continue;
    const Eigen::Vector2d g = kin_.GravityTorque(leg, q1, q2, g_trunk);
    Eigen::Vector2d rhs;
    for (int k = 0; k < 2; ++k) {
      const int j = 2 * i + k;
      rhs[k] = model_.armature_kgm2 * qdd[j] + model_.damping_nms * at.velocity_rad_s[j] - at.torque_nm[j] - g[k];
    }
    const Eigen::Vector2d f = Js.transpose().fullPivLu().solve(rhs);  // (F_x, F_z)
    out.f_trunk[i] = Eigen::Vector3d(f[0], 0.0, f[1]);
    out.valid[i] = true;
  }
  return out;
}

}  // namespace viqu::lo

#include "slam/lo/foot_force.h"

#include <cmath>

namespace viqu::lo {

FootForceEstimator::FootForceEstimator(const kin::LegKinematics& kin, const FootForceModel& model)
    : kin_(kin), model_(model) {}

FootForces FootForceEstimator::Update(const JointState& js, const Eigen::Vector3d& g_trunk) {
  FootForces out;
  out.t_ns = js.t_ns;
  std::array<double, kNumJoints> qdd{};
  if (have_last_ && js.t_ns > last_t_ns_) {
    const double dt = 1e-9 * static_cast<double>(js.t_ns - last_t_ns_);
    for (int j = 0; j < kNumJoints; ++j) qdd[j] = (js.velocity_rad_s[j] - last_velocity_[j]) / dt;
  }
  have_last_ = true;
  last_t_ns_ = js.t_ns;
  last_velocity_ = js.velocity_rad_s;
  if (!js.has_torque) return out;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg leg = static_cast<Leg>(i);
    const int j1 = 2 * i, j2 = 2 * i + 1;
    const double q1 = js.position_rad[j1], q2 = js.position_rad[j2];
    const Eigen::Matrix<double, 3, 2> J = kin_.FootJacobian(leg, q1, q2);
    Eigen::Matrix2d Js;  // rows x and z of the trunk frame
    Js.row(0) = J.row(0);
    Js.row(1) = J.row(2);
    if (!(std::abs(Js.determinant()) >= model_.min_jacobian_det_m2)) continue;
    const Eigen::Vector2d g = kin_.GravityTorque(leg, q1, q2, g_trunk);
    Eigen::Vector2d rhs;
    for (int k = 0; k < 2; ++k) {
      const int j = 2 * i + k;
      rhs[k] = model_.armature_kgm2 * qdd[j] + model_.damping_nms * js.velocity_rad_s[j] - js.torque_nm[j] - g[k];
    }
    const Eigen::Vector2d f = Js.transpose().fullPivLu().solve(rhs);  // (F_x, F_z)
    out.f_trunk[i] = Eigen::Vector3d(f[0], 0.0, f[1]);
    out.valid[i] = true;
  }
  return out;
}

}  // namespace viqu::lo

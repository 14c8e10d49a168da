#include "runner/slip_oracle.h"

namespace viqu::runner {

void SlipOracle::Add(const JointState& js, const Eigen::Isometry3d& T_w_body, const Eigen::Vector3d& w_body,
                     const std::array<bool, kNumLegs>& contact) {
  const double dt = last_ns_ ? (js.t_ns - *last_ns_) * 1e-9 : 0.0;
  last_ns_ = js.t_ns;
  const Eigen::Matrix3d R = T_w_body.linear();
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg leg = static_cast<Leg>(i);
    const double q1 = js.position_rad[2 * i], q2 = js.position_rad[2 * i + 1];
    const Eigen::Vector3d centre_w = T_w_body.translation() + R * kin_.FootInTrunk(leg, q1, q2);
    const Eigen::Vector3d w_foot_w =
        R * (w_body + kin_.ShankAngularVelocity(leg, js.velocity_rad_s[2 * i], js.velocity_rad_s[2 * i + 1]));
    const Eigen::Vector3d roll_w = w_foot_w.cross(Eigen::Vector3d(0, 0, kin_.foot_radius()));
    if (!contact[i]) {
      in_contact_[i] = false;
      slipped_[i] = false;
      travel_m_[i] = 0;
      continue;
    }
    if (!in_contact_[i]) {
      in_contact_[i] = true;
      rolled_w_[i].setZero();
      anchor_w_[i] = centre_w;
    } else {
      rolled_w_[i] += roll_w * dt;
    }
    travel_m_[i] = (centre_w - rolled_w_[i] - anchor_w_[i]).head<2>().norm();
    slipped_[i] = slipped_[i] || travel_m_[i] > slip_travel_m_;
  }
}

}  // namespace viqu::runner

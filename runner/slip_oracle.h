#pragma once
// The slip-by-travel decision (lo.slip_travel_m) run on the simulator's truth for everything but
// the encoders: the true trunk pose and rate and the true (debounced) contact, with the measured
// joint angles through the URDF kinematics and the same rolling model as the estimator. It is the
// best that decision can do with these encoders (issue 55 item 6's oracle), scored as slip.oracle.*
// beside the estimator's own (metrics only).
#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/leg_kinematics.h"
#include "slam/measurements/joint_state.h"

namespace viqu::runner {

class SlipOracle {
 public:
  SlipOracle(const kin::LegKinematics& kin, double slip_travel_m) : kin_(kin), slip_travel_m_(slip_travel_m) {}

  // One encoder reading with the truth at its time: trunk pose, trunk rate (trunk frame, rad/s)
  // and each foot's contact.
  void Add(const JointState& js, const Eigen::Isometry3d& T_w_body, const Eigen::Vector3d& w_body,
           const std::array<bool, kNumLegs>& contact);

  const std::array<bool, kNumLegs>& slipped() const { return slipped_; }
  const std::array<double, kNumLegs>& travel_m() const { return travel_m_; }

 private:
  const kin::LegKinematics& kin_;
  double slip_travel_m_;
  std::optional<int64_t> last_ns_;
  std::array<bool, kNumLegs> in_contact_{};
  std::array<Eigen::Vector3d, kNumLegs> rolled_w_{}, anchor_w_{};
  std::array<double, kNumLegs> travel_m_{};
  std::array<bool, kNumLegs> slipped_{};
};

}  // namespace viqu::runner

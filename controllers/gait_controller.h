#pragma once
// Turns a body command (forward speed, yaw rate) into joint position targets: a periodic gait
// schedule, a foot trajectory per leg in the trunk frame, and inverse kinematics. Turning is
// done by stepping the left and right legs at different speeds (the legs have no abduction).
#include <array>

#include "controllers/body_command.h"
#include "controllers/gait_schedule.h"
#include "kinematics/leg_kinematics.h"
#include "scenario/scenario.h"

namespace viqu::ctrl {

struct GaitControllerOptions {
  double stand_height_m = 0.075;  // trunk centre above the floor while standing (m)
  double foot_radius_m = 0.006;   // foot sphere radius (m): foot centre stays this high in stance
  double max_stride_m = 0.05;     // longest step a leg may take (m)
  double foot_x_offset_m = 0.0;   // nominal foot position ahead of the hip (m)
  double inset_m = 0.035;          // nominal feet moved this far toward the trunk centre in x (m):
                                  // shorter yaw lever, so differential stepping turns better
  double max_accel_mps2 = 0.5;    // command slew limit, forward (m/s^2)
  double max_yaw_accel_rps2 = 4;  // command slew limit, yaw (rad/s^2)
};

class GaitController {
 public:
  GaitController(const kin::LegKinematics& kin, const GaitConfig& gait,
                 const GaitControllerOptions& opt = {});

  // Joint targets (rad, order of JointState) for standing still at the nominal height.
  std::array<double, kNumJoints> StandingTargets() const;

  // Advances the controller by dt_s under `cmd` and returns the joint targets.
  std::array<double, kNumJoints> Update(double dt_s, const BodyCommand& cmd);

  // Planned contact of every leg (true while standing).
  std::array<bool, kNumLegs> planned_stance() const { return stance_; }

  // The foot targets (trunk frame, m) of the last Update.
  const std::array<Eigen::Vector3d, kNumLegs>& foot_targets() const { return targets_; }

  bool stepping() const { return stepping_; }

 private:
  Eigen::Vector3d NominalFoot(Leg leg) const;
  std::array<double, kNumJoints> SolveIk(const std::array<Eigen::Vector3d, kNumLegs>& feet) const;

  const kin::LegKinematics& kin_;
  GaitSchedule schedule_;
  GaitConfig gait_;
  GaitControllerOptions opt_;
  BodyCommand cmd_;                            // slew-limited command in use
  double cycle_phase_ = 0;                     // [0, 1)
  bool stepping_ = false;
  double idle_time_s_ = 0;                     // time with a zero command while stepping (s)
  std::array<bool, kNumLegs> stance_{{true, true, true, true}};
  std::array<double, kNumLegs> foot_x_{};      // foot x offset from its nominal position (m)
  std::array<double, kNumLegs> liftoff_x_{};   // foot x offset when its swing began (m)
  std::array<Eigen::Vector3d, kNumLegs> targets_;
};

}  // namespace viqu::ctrl

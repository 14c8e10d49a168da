#pragma once
// The robot side of a run: kinematics from the URDF, the gait controller, the steering
// (waypoints or a velocity schedule) and the simulated world, wired for one control step.
#include <memory>
#include <optional>

#include "controllers/gait_controller.h"
#include "controllers/waypoint_follower.h"
#include "kinematics/leg_kinematics.h"
#include "scenario/scenario.h"
#include "sim/world.h"

namespace viqu::runner {

class RobotRig {
 public:
  // Throws viqu::InputError when the URDF beside the robot's MJCF is missing or invalid.
  explicit RobotRig(const Scenario& s);

  // Steering command for time t_s given the pose to steer by.
  ctrl::BodyCommand Command(double t_s, const ctrl::Pose2& pose);

  // One physics step: command from `steer_pose`, gait update, servo targets, world step.
  void Step(const ctrl::Pose2& steer_pose);

  // The ground-truth planar pose of the trunk.
  ctrl::Pose2 TruePose2() const;

  sim::World& world() { return *world_; }
  const sim::World& world() const { return *world_; }
  const kin::LegKinematics& kinematics() const { return kin_; }
  const ctrl::GaitController& gait() const { return *gait_; }
  bool waypoints_done() const { return follower_ && follower_->done(); }

 private:
  kin::LegKinematics kin_;
  std::unique_ptr<ctrl::GaitController> gait_;
  std::unique_ptr<sim::World> world_;
  std::optional<ctrl::WaypointFollower> follower_;
  std::optional<ctrl::VelocitySchedule> schedule_;
};

// The planar pose (x, y, heading of the trunk's x axis) of a trunk pose in the world.
ctrl::Pose2 Pose2Of(const Eigen::Isometry3d& T_w_body);

// The URDF that describes the same robot as an MJCF file: same folder and stem, ".urdf".
std::string UrdfBesideMjcf(const std::string& mjcf_path);

}  // namespace viqu::runner

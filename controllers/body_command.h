#pragma once

namespace viqu::ctrl {

// What the robot is asked to do now, in its own frame.
struct BodyCommand {
  double forward_mps = 0;   // forward speed (m/s)
  double yaw_rate_rps = 0;  // yaw rate (rad/s), positive turns left
};

// Planar pose of the trunk used for steering (from ground truth or from the estimate).
struct Pose2 {
  double x = 0, y = 0;  // world position (m)
  double yaw = 0;       // heading (rad)
};

}  // namespace viqu::ctrl

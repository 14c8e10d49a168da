#pragma once
// Steers toward a list of waypoints by a pose source (ground truth or the SLAM estimate).
#include <vector>

#include "controllers/body_command.h"
#include "scenario/scenario.h"

namespace viqu::ctrl {

struct WaypointFollowerOptions {
  double reach_radius_m = 0.06;      // a waypoint counts as reached within this distance (m)
  double yaw_gain = 2.5;             // yaw rate per heading error (1/s)
  double max_yaw_rate_rps = 1.2;     // (rad/s)
  double turn_in_place_rad = 0.8;    // heading errors above this stop forward motion (rad)
  double slow_down_radius_m = 0.15;  // speed ramps down to the final waypoint within this (m)
};

class WaypointFollower {
 public:
  WaypointFollower(std::vector<Vec2> waypoints, double speed_mps, bool loop,
                   const WaypointFollowerOptions& opt = {});

  // The command for the current pose; advances through reached waypoints.
  BodyCommand Update(const Pose2& pose);

  bool done() const { return done_; }            // the last waypoint was reached (no loop)
  size_t current_index() const { return index_; }

 private:
  std::vector<Vec2> waypoints_;
  double speed_mps_;
  bool loop_;
  WaypointFollowerOptions opt_;
  size_t index_ = 0;
  bool done_ = false;
};

// A velocity schedule: the command of the last entry whose start time has passed.
class VelocitySchedule {
 public:
  explicit VelocitySchedule(std::vector<VelocityCommand> entries);
  BodyCommand At(double t_s) const;

 private:
  std::vector<VelocityCommand> entries_;
};

}  // namespace viqu::ctrl

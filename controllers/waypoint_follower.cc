#include "controllers/waypoint_follower.h"

#include <algorithm>
#include <cmath>

#include "common/errors.h"

namespace viqu::ctrl {
namespace {

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

WaypointFollower::WaypointFollower(std::vector<Vec2> waypoints, double speed_mps, bool loop,
                                   const WaypointFollowerOptions& opt)
    : waypoints_(std::move(waypoints)), speed_mps_(speed_mps), loop_(loop), opt_(opt) {
  done_ = waypoints_.empty();
}

BodyCommand WaypointFollower::Update(const Pose2& pose) {
  BodyCommand cmd;
  while (!done_) {
    const Vec2& w = waypoints_[index_];
    const double dx = w[0] - pose.x, dy = w[1] - pose.y;
    const double dist = std::hypot(dx, dy);
    if (dist < opt_.reach_radius_m) {
      if (index_ + 1 < waypoints_.size()) {
        ++index_;
      } else if (loop_) {
        index_ = 0;
      } else {
        done_ = true;
      }
      continue;
    }
    const double err = WrapAngle(std::atan2(dy, dx) - pose.yaw);
    cmd.yaw_rate_rps = std::clamp(opt_.yaw_gain * err, -opt_.max_yaw_rate_rps, opt_.max_yaw_rate_rps);
    double v = speed_mps_ * std::max(0.0, std::cos(err));
    if (std::abs(err) > opt_.turn_in_place_rad) v = 0;
    const bool last = !loop_ && index_ + 1 == waypoints_.size();
    if (last) v *= std::min(1.0, dist / opt_.slow_down_radius_m + 0.2);
    cmd.forward_mps = v;
    break;
  }
  return cmd;
}

VelocitySchedule::VelocitySchedule(std::vector<VelocityCommand> entries) : entries_(std::move(entries)) {
  for (size_t i = 1; i < entries_.size(); ++i) {
    if (entries_[i].t_s < entries_[i - 1].t_s) throw InputError("velocity schedule times must not decrease");
  }
}

BodyCommand VelocitySchedule::At(double t_s) const {
  BodyCommand cmd;
  for (const VelocityCommand& e : entries_) {
    if (e.t_s > t_s) break;
    cmd.forward_mps = e.forward_mps;
    cmd.yaw_rate_rps = e.yaw_rate_dps * M_PI / 180.0;
  }
  return cmd;
}

}  // namespace viqu::ctrl

#pragma once
// Moving a trajectory to another frame on the same body (ToIsometry / ToStampedPose are in the
// measurement header).
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "slam/measurements/ground_truth_pose.h"

namespace viqu::io {

// From poses T_w_x of frame x to poses T_w_y = T_w_x * T_x_y of frame y (same stamps).
inline std::vector<StampedPose> ChangeTrajectoryFrame(const std::vector<StampedPose>& T_w_x,
                                                      const Eigen::Isometry3d& T_x_y) {
  std::vector<StampedPose> out;
  out.reserve(T_w_x.size());
  for (const StampedPose& p : T_w_x) out.push_back(ToStampedPose(p.t_ns, ToIsometry(p) * T_x_y));
  return out;
}

}  // namespace viqu::io

#pragma once
// StampedPose <-> Eigen::Isometry3d, and moving a trajectory to another frame on the same body.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "slam/measurements/ground_truth_pose.h"

namespace viqu::io {

inline Eigen::Isometry3d ToIsometry(const StampedPose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = p.q_w_x.normalized().toRotationMatrix();
  T.translation() = p.p_w_x;
  return T;
}

inline StampedPose ToStampedPose(int64_t t_ns, const Eigen::Isometry3d& T_w_x) {
  StampedPose p;
  p.t_ns = t_ns;
  p.q_w_x = Eigen::Quaterniond(T_w_x.linear()).normalized();
  p.p_w_x = T_w_x.translation();
  return p;
}

// From poses T_w_x of frame x to poses T_w_y = T_w_x * T_x_y of frame y (same stamps).
inline std::vector<StampedPose> ChangeTrajectoryFrame(const std::vector<StampedPose>& T_w_x,
                                                      const Eigen::Isometry3d& T_x_y) {
  std::vector<StampedPose> out;
  out.reserve(T_w_x.size());
  for (const StampedPose& p : T_w_x) out.push_back(ToStampedPose(p.t_ns, ToIsometry(p) * T_x_y));
  return out;
}

}  // namespace viqu::io

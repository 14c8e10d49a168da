#pragma once
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace viqu {

// A rigid pose with its time: T_w_x maps points from frame x to the world frame w.
struct StampedPose {
  int64_t t_ns = 0;                 // simulated time (ns)
  Eigen::Quaterniond q_w_x = Eigen::Quaterniond::Identity();
  Eigen::Vector3d p_w_x = Eigen::Vector3d::Zero();  // (m)
};

// The pose as a rigid transform (the quaternion normalised).
inline Eigen::Isometry3d ToIsometry(const StampedPose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = p.q_w_x.normalized().toRotationMatrix();
  T.translation() = p.p_w_x;
  return T;
}

// A rigid transform T_w_x with its time as a StampedPose (unit quaternion).
inline StampedPose ToStampedPose(int64_t t_ns, const Eigen::Isometry3d& T_w_x) {
  StampedPose p;
  p.t_ns = t_ns;
  p.q_w_x = Eigen::Quaterniond(T_w_x.linear()).normalized();
  p.p_w_x = T_w_x.translation();
  return p;
}

// Ground truth of the robot at one instant.
struct GroundTruthState {
  int64_t t_ns = 0;                 // simulated time (ns)
  StampedPose T_w_body;             // trunk (IMU) frame in world
  StampedPose T_w_cam;              // left camera optical frame in world (x right, y down, z fwd)
  Eigen::Vector3d vel_w_body = Eigen::Vector3d::Zero();  // trunk linear velocity in world (m/s)
};

}  // namespace viqu

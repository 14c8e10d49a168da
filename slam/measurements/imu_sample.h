#pragma once
#include <cstdint>

#include <Eigen/Core>

namespace viqu {

// One IMU reading in the IMU (body) frame: x forward, y left, z up.
struct ImuSample {
  int64_t t_ns = 0;              // simulated time (ns)
  Eigen::Vector3d accel_i = Eigen::Vector3d::Zero();  // specific force incl. gravity reaction (m/s^2); +9.81 z at rest
  Eigen::Vector3d gyro_i = Eigen::Vector3d::Zero();   // angular velocity (rad/s)
};

}  // namespace viqu

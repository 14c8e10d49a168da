#pragma once
#include <array>
#include <cstdint>

namespace viqu {

// Leg order everywhere: front-left, front-right, back-left, back-right (paper: FL, FR, BL, BR).
enum class Leg : int { kFL = 0, kFR = 1, kBL = 2, kBR = 3 };
constexpr int kNumLegs = 4;
constexpr int kJointsPerLeg = 2;  // hip/shoulder pitch theta1, knee/elbow pitch theta2
constexpr int kNumJoints = kNumLegs * kJointsPerLeg;

// "FL", "FR", "BL", "BR": the prefix of the leg's joint, actuator, site and geom names.
inline const char* LegName(Leg leg) {
  static const char* const kNames[kNumLegs] = {"FL", "FR", "BL", "BR"};
  return kNames[static_cast<int>(leg)];
}

// Encoder reading of all joints plus the contact state of every foot, and the servos' torque.
struct JointState {
  int64_t t_ns = 0;                              // simulated time (ns)
  std::array<double, kNumJoints> position_rad{};  // [leg*2 + 0] = theta1, [leg*2 + 1] = theta2 (rad)
  std::array<double, kNumJoints> velocity_rad_s{};  // (rad/s)
  std::array<bool, kNumLegs> contact{};           // foot touches the ground (truth from the simulator)
  // The torque each servo reports applying to its joint (N m, same order; motor current as
  // torque, with its sensor's noise, bias, quantisation and delay). Which instant it belongs to:
  // sensors.joints.torque_sampling (scenario.h). Recordings made before torque sensing have none.
  std::array<double, kNumJoints> torque_nm{};
  bool has_torque = false;                       // torque_nm holds a reading
};

}  // namespace viqu

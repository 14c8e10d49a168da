#pragma once
#include <array>
#include <cstdint>

#include "slam/measurements/joint_state.h"

namespace viqu {

// Which feet are on the ground by a source the estimator may use: the gait controller's planned
// stance (published as a real robot's controller would) or the foot touch sensors. Never the
// simulator's contact truth (JointState::contact), which only metrics may read.
struct ContactReading {
  int64_t t_ns = 0;                      // simulated time (ns)
  std::array<bool, kNumLegs> stance{};   // foot on the ground, legs FL, FR, BL, BR
};

}  // namespace viqu

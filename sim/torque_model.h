#pragma once
// Joint torque sensor model: a servo's motor current read as the torque it applies (issue 55).
// Pure C++ on plain inputs (no MuJoCo); the simulator feeds it the actuator torques of the eight
// leg joints (sim::World::JointTorques or its mean over the reading's interval).
#include <array>
#include <cstdint>
#include <deque>
#include <random>

#include "scenario/scenario.h"
#include "slam/measurements/joint_state.h"

namespace viqu::sim {

// Per joint j and reading k (at the encoder's rate):
//   torque_k = Q(tau_{k - d} + b_j + n),  n ~ N(0, torque_noise_nm^2),  b_j ~ N(0, torque_bias_nm^2)
// drawn once per joint when the model is made; Q(x) = torque_resolution_nm * round(x / step)
// (the identity when the step is 0); d = round(torque_delay_s * rate_hz) readings (before d
// readings have passed, the first torque given stands in for the older ones: runs start at rest).
// The generator is the model's own (seeded by the caller from the run's seed): reading torques
// changes no other sensor's draws.
class TorqueModel {
 public:
  // Throws viqu::InputError for a non-positive rate or a negative noise, bias, step or delay.
  TorqueModel(const viqu::JointsConfig& config, uint64_t seed);

  // tau: the joints' torques (N m), index leg*2 + {0: hip, 1: knee}. Throws viqu::InputError for
  // a non-finite value; a rejected call leaves the model unchanged.
  std::array<double, viqu::kNumJoints> Measure(const std::array<double, viqu::kNumJoints>& tau);

  // Each joint's constant offset b_j (N m).
  const std::array<double, viqu::kNumJoints>& bias_nm() const { return bias_nm_; }
  // The delay in readings, d.
  int delay_readings() const { return delay_readings_; }

 private:
  double Quantise(double x) const;

  viqu::JointsConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::array<double, viqu::kNumJoints> bias_nm_{};
  int delay_readings_ = 0;
  std::deque<std::array<double, viqu::kNumJoints>> history_;  // the last delay_readings_ + 1 torques
};

}  // namespace viqu::sim

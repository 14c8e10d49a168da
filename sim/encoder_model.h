#pragma once
// Joint encoder model: Gaussian noise, then quantisation to the encoder's resolution; velocity
// from the finite difference of consecutive measured positions. Pure C++ on plain inputs (no
// MuJoCo); the simulator feeds it qpos/qvel of the eight leg joints and the foot contacts.
#include <array>
#include <cstdint>
#include <optional>
#include <random>

#include "scenario/scenario.h"
#include "slam/measurements/joint_state.h"

namespace viqu::sim {

// Per joint and reading:
//   position = Q(q + N(0, noise_rad^2)),  Q(x) = resolution * round(x / resolution)
//              (Q is the identity when resolution_rad == 0)
//   velocity = (position_k - position_{k-1}) / (t_k - t_{k-1})
// Velocity is a backward finite difference of the *measured* positions, as a servo or encoder
// board without a tachometer reports it: it lags by half a sample and carries the position noise
// amplified by sqrt(2)/dt (about 0.4 rad/s std at 200 Hz with the default noise and resolution).
// We chose this over "true velocity + independent noise" because it is what a real encoder gives
// and keeps position and velocity consistent. The first reading has no predecessor: its velocity
// is the true qd (a single sample; runs start at rest).
// Contacts are passed through unchanged (ground truth of the simulator).
class EncoderModel {
 public:
  // Throws viqu::InputError for a non-positive rate or a negative noise / resolution.
  EncoderModel(const viqu::JointsConfig& config, uint64_t seed);

  // q: joint angles (rad), qd: joint velocities (rad/s), index leg*2 + {0: hip, 1: knee} with legs
  // FL, FR, BL, BR; contact: foot contact per leg. Throws viqu::InputError for non-finite q or qd
  // or a timestamp that does not increase; a rejected call leaves the model unchanged.
  viqu::JointState Measure(int64_t t_ns, const std::array<double, viqu::kNumJoints>& q,
                           const std::array<double, viqu::kNumJoints>& qd,
                           const std::array<bool, viqu::kNumLegs>& contact);

 private:
  double Quantise(double x) const;

  viqu::JointsConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::optional<int64_t> last_t_ns_;                   // previous reading's time (ns)
  std::array<double, viqu::kNumJoints> last_position_rad_{};  // previous measured positions (rad)
};

}  // namespace viqu::sim

#pragma once
// Which legs are in stance when: a periodic schedule of phase offsets (trot or walk).
#include <array>
#include <string>

#include "slam/measurements/joint_state.h"

namespace viqu::ctrl {

struct LegPhase {
  bool stance = true;     // foot on the ground by plan
  double progress = 0;    // fraction of the current stance or swing period done, [0, 1)
};

class GaitSchedule {
 public:
  // type: "trot" (diagonal pairs, half a cycle apart) or "walk" (one leg at a time: FL, BR, FR,
  // BL a quarter cycle apart). Throws viqu::InputError on another type or duty outside (0, 1).
  GaitSchedule(const std::string& type, double frequency_hz, double duty);

  // Phase of a leg given the gait cycle phase in [0, 1).
  LegPhase PhaseOf(Leg leg, double cycle_phase) const;

  double frequency_hz() const { return frequency_hz_; }  // (Hz)
  double duty() const { return duty_; }                  // stance fraction
  double stance_duration_s() const { return duty_ / frequency_hz_; }
  double swing_duration_s() const { return (1 - duty_) / frequency_hz_; }

 private:
  double frequency_hz_;
  double duty_;
  std::array<double, kNumLegs> offset_{};  // phase offset of each leg's stance start
};

}  // namespace viqu::ctrl

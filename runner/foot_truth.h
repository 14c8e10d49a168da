#pragma once
// The simulator's truth about the feet, every physics step (metrics only, issue 55 item 6): each
// foot's contact, debounced, and its stances with the sole's net horizontal travel while in
// contact. A stance whose net travel from its touch-down point exceeds scoring.slip_travel_m at
// some instant is a true slip event; that instant (the first) is where a detection's latency is
// measured from.
//
// The sole is the foot's material point at its lowest point (sim::World::FootSoleVelocityWorld):
// a foot that rolls without sliding has it at rest, so rolling adds no travel. Its velocity is
// integrated every physics step (1 ms), not at the encoder ticks, so that a 3 mm slide is seen
// whole.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slam/measurements/joint_state.h"

namespace viqu::runner {

struct TrueStance {
  int leg = 0;
  int64_t touchdown_ns = 0, liftoff_ns = 0;  // debounced contact start, end (the end of the run if still down)
  double travel_m = 0;                       // largest net horizontal displacement of the sole from where it
                                             // touched down, over the stance (m)
  int64_t crossed_ns = -1;                   // first instant the net travel exceeded the slip travel, or -1
  double peak_speed_mps = 0;                 // the sole's largest horizontal speed over the stance (m/s)
  bool from_start = false;                   // the foot was down when the run began (no true touch-down)
  bool to_end = false;                       // still down when the run ended (no true lift-off)
};

class FootTruth {
 public:
  // slip_travel_m, debounce_s: the scenario's scoring settings.
  FootTruth(double slip_travel_m, double debounce_s) : slip_travel_m_(slip_travel_m), debounce_s_(debounce_s) {
    // Eigen's vectors start uninitialised: every accumulator starts at zero.
    for (int i = 0; i < kNumLegs; ++i) {
      travel_[i].setZero();
      pending_[i].setZero();
    }
  }

  // After one physics step of dt_s ending at t_ns: each foot's raw contact and sole velocity
  // (world). The first call (dt_s 0 at the run's start) takes the feet down then as in stance.
  void Step(int64_t t_ns, double dt_s, const std::array<bool, kNumLegs>& raw_contact,
            const std::array<Eigen::Vector3d, kNumLegs>& sole_velocity_w);

  // The debounced contact now, and the current stance's net travel so far (m, 0 in swing).
  const std::array<bool, kNumLegs>& contact() const { return contact_; }
  double travel_m(int leg) const { return contact_[leg] ? travel_[leg].norm() : 0.0; }

  // Every stance so far, the ones still going closed at t_end_ns, ordered by touch-down.
  std::vector<TrueStance> Finish(int64_t t_end_ns);

 private:
  void Close(int leg, int64_t t_ns);

  double slip_travel_m_, debounce_s_;
  bool started_ = false;
  std::array<bool, kNumLegs> contact_{};
  // Physics steps in a row the raw contact has differed from contact_, and since when (ns).
  std::array<int, kNumLegs> differing_{};
  std::array<int64_t, kNumLegs> differ_since_ns_{};
  std::array<Eigen::Vector2d, kNumLegs> travel_{};    // net travel of the current stance (m)
  std::array<Eigen::Vector2d, kNumLegs> pending_{};   // travel while a change is not yet confirmed (m)
  std::array<double, kNumLegs> pending_peak_{};       // and the largest speed then (m/s)
  std::array<TrueStance, kNumLegs> open_{};
  std::vector<TrueStance> stances_;
};

}  // namespace viqu::runner

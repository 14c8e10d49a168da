#pragma once
// How fast the viewer lets a run go: pause, single steps of one camera frame, and a speed in
// simulated seconds per wall-clock second. Pure logic (no window), so that it is testable.
#include <cstdint>

namespace viqu::viewer {

class Playback {
 public:
  static constexpr double kMaxSpeed = 64.0;        // fastest paced speed (x real time)
  static constexpr double kMinSpeed = 1.0 / 64.0;  // slowest (x real time)
  // A run more than this far behind its pace (wall s) stops trying to catch up: the pace starts
  // again from the frame shown, instead of rushing through frames to make up for a slow stretch.
  static constexpr double kMaxLagS = 0.25;

  // `speed`: simulated s per wall s; 0 = as fast as the run goes (no pacing).
  explicit Playback(double speed, bool paused = false);

  void TogglePause();
  // Pauses and lets one more frame through; steps asked for before they are taken add up.
  void Step();
  // Doubles / halves the speed (within kMinSpeed..kMaxSpeed); from unpaced, Slower goes to kMaxSpeed.
  void Faster();
  void Slower();
  void SetSpeed(double speed);  // 0 = unpaced

  bool paused() const { return paused_; }
  double speed() const { return speed_; }

  // Whether the next frame may be shown now: not paused, or a step is pending (which this
  // takes).
  bool TakeFrame();

  // Wall time to wait (s, >= 0) before showing the frame of simulated time `t_s` when the wall
  // clock reads `now_s`, so that simulated time runs at `speed` x wall time from the frame where
  // the pace last started (a resume, a speed change, a step, a lag over kMaxLagS restart it).
  double WaitBefore(double t_s, double now_s);

 private:
  void Restart() { anchored_ = false; }

  double speed_;
  bool paused_;
  int steps_pending_ = 0;
  bool anchored_ = false;
  double anchor_t_s_ = 0, anchor_wall_s_ = 0;
};

}  // namespace viqu::viewer

#include "viewer/playback.h"

#include <algorithm>

namespace viqu::viewer {

Playback::Playback(double speed, bool paused) : paused_(paused) { SetSpeed(speed); }

void Playback::TogglePause() {
  paused_ = !paused_;
  steps_pending_ = 0;
  Restart();
}

void Playback::Step() {
  paused_ = true;
  ++steps_pending_;
  Restart();
}

void Playback::Faster() { SetSpeed(speed_ == 0 ? 0 : speed_ * 2); }

void Playback::Slower() { SetSpeed(speed_ == 0 ? kMaxSpeed : speed_ / 2); }

void Playback::SetSpeed(double speed) {
  speed_ = speed <= 0 ? 0 : std::clamp(speed, kMinSpeed, kMaxSpeed);
  Restart();
}

bool Playback::TakeFrame() {
  if (!paused_) return true;
  if (steps_pending_ == 0) return false;
  --steps_pending_;
  return true;
}

double Playback::WaitBefore(double t_s, double now_s) {
  if (speed_ == 0 || paused_) {  // unpaced, or a single step: show it at once
    Restart();
    return 0;
  }
  if (!anchored_) {
    anchored_ = true;
    anchor_t_s_ = t_s;
    anchor_wall_s_ = now_s;
    return 0;
  }
  const double due_s = anchor_wall_s_ + (t_s - anchor_t_s_) / speed_;
  if (now_s - due_s > kMaxLagS) {  // too slow to keep the pace: start it again from here
    anchor_t_s_ = t_s;
    anchor_wall_s_ = now_s;
    return 0;
  }
  return std::max(0.0, due_s - now_s);
}

}  // namespace viqu::viewer

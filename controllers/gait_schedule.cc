#include "controllers/gait_schedule.h"

#include <cmath>

#include "common/errors.h"

namespace viqu::ctrl {

GaitSchedule::GaitSchedule(const std::string& type, double frequency_hz, double duty)
    : frequency_hz_(frequency_hz), duty_(duty) {
  if (!(duty > 0 && duty < 1)) throw InputError("gait duty must be in (0, 1), got " + std::to_string(duty));
  if (!(frequency_hz > 0)) throw InputError("gait frequency must be > 0 Hz");
  if (type == "trot") {
    offset_ = {0.0, 0.5, 0.5, 0.0};  // FL+BR together, FR+BL half a cycle later
  } else if (type == "walk") {
    offset_ = {0.0, 0.5, 0.75, 0.25};  // FL, BR, FR, BL
  } else {
    throw InputError("unknown gait type '" + type + "' (expected trot or walk)");
  }
}

LegPhase GaitSchedule::PhaseOf(Leg leg, double cycle_phase) const {
  double p = cycle_phase - offset_[static_cast<int>(leg)];
  p -= std::floor(p);
  LegPhase out;
  if (p < duty_) {
    out.stance = true;
    out.progress = p / duty_;
  } else {
    out.stance = false;
    out.progress = (p - duty_) / (1 - duty_);
  }
  return out;
}

}  // namespace viqu::ctrl

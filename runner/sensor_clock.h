#pragma once
#include <cmath>
#include <cstdint>

namespace viqu::runner {

// Fires at a fixed rate on the simulated clock: at t = 0, period, 2 period, ...
class SensorClock {
 public:
  explicit SensorClock(double rate_hz) : period_ns_(std::llround(1e9 / rate_hz)) {}
  // True (and advances) when the tick at or before t_ns has not fired yet.
  bool Due(int64_t t_ns) {
    if (t_ns < next_ns_) return false;
    next_ns_ += period_ns_;
    return true;
  }
  int64_t period_ns() const { return period_ns_; }

 private:
  int64_t period_ns_;    // (ns)
  int64_t next_ns_ = 0;  // time of the next tick (ns)
};

}  // namespace viqu::runner

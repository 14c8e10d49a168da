#pragma once
// Slip events of the feet, true and detected, and how well the detections match the truth.
// A true slip event is a run of samples in which a foot touches the ground (simulator contact)
// while its sole slides faster than 0.05 m/s, lasting at least 20 ms (issue 8's definition). A
// detected event is a run of samples the estimator flagged as slipping. A detected event is
// correct when it overlaps a true event of the same foot (within a tolerance); a true event is
// found when a detected event overlaps it. slip.csv lists every event of both kinds.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/json_writer.h"
#include "slam/measurements/joint_state.h"

namespace viqu::runner {

constexpr double kSlipSpeedMps = 0.05;    // true slip: sole speed above this in contact (m/s), issue 8
constexpr double kSlipMinDurationS = 0.02;  // true slip: lasting at least this (s), issue 8
constexpr double kSlipMatchToleranceS = 0.02;  // detections this close to a true event match it (s):
                                               // one encoder sample of lag either way, plus margin

struct SlipEvent {
  int leg = 0;
  int64_t start_ns = 0, end_ns = 0;  // first sample, last sample + one period (ns)
  double peak = 0;                   // largest value over the event (sole speed m/s, or Mahalanobis^2)
  bool matched = false;
};

// Runs of "on" samples per foot, at a fixed sample period.
class SlipEventBuilder {
 public:
  explicit SlipEventBuilder(double min_duration_s) : min_duration_ns_(std::llround(min_duration_s * 1e9)) {}
  void Add(int64_t t_ns, int64_t period_ns, const std::array<bool, kNumLegs>& on,
           const std::array<double, kNumLegs>& value);
  std::vector<SlipEvent> Finish();

 private:
  void Close(int leg);
  int64_t min_duration_ns_;
  std::array<bool, kNumLegs> open_{};
  std::array<SlipEvent, kNumLegs> current_{};
  std::vector<SlipEvent> events_;
};

struct SlipScore {
  int truth_events = 0, detected_events = 0;
  int true_found = 0, detections_correct = 0;
  double precision = 0, recall = 0;  // 1 when there is nothing to find / nothing detected
};

// Marks matched events of both lists and scores them.
SlipScore ScoreSlip(std::vector<SlipEvent>* truth, std::vector<SlipEvent>* detected, double tolerance_s);

// slip.csv: kind (truth|detected), leg, start_s, end_s, peak, matched.
std::string SlipCsv(const std::vector<SlipEvent>& truth, const std::vector<SlipEvent>& detected);

}  // namespace viqu::runner

#pragma once
// Slip events of the feet, true and detected, and how well the detections match the truth
// (issue 55 item 6; the scenario's `scoring` block holds the numbers).
//  - A true slip event is one stance of one foot whose sole's net horizontal displacement from its
//    touch-down point exceeds scoring.slip_travel_m (runner/foot_truth.h); it spans the stance.
//  - A detection is the estimator's: per foot and estimated stance, the first sample it flagged
//    as slipping starts one, which lasts to its last flagged sample of that stance.
//  - They match one to one, foot by foot: a detection whose onset lies within
//    [start - slip_match_before_s, end + slip_match_after_s] of a true event takes the earliest
//    such event not yet taken. Precision is the share of detections matched, recall the share of
//    true events matched; latency is the onset minus the instant the travel crossed the threshold.
// slip.csv lists every event of both kinds.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "runner/foot_truth.h"
#include "slam/measurements/joint_state.h"

namespace viqu::runner {

struct SlipEvent {
  int leg = 0;
  int64_t start_ns = 0, end_ns = 0;  // truth: the stance; detection: first to last flagged sample + one period
  int64_t crossed_ns = -1;           // truth: the instant the travel crossed the threshold (-1 for detections)
  double size = 0;                   // truth: travel (m); detection: largest gate statistic (Mahalanobis^2)
  bool matched = false;
};

// The true slip events among the stances: those that crossed the travel threshold.
std::vector<SlipEvent> TrueSlipEvents(const std::vector<TrueStance>& stances);

// Detections from the estimator's per-sample contact and slip flags.
class SlipDetectionBuilder {
 public:
  void Add(int64_t t_ns, int64_t period_ns, const std::array<bool, kNumLegs>& contact,
           const std::array<bool, kNumLegs>& flagged, const std::array<double, kNumLegs>& value);
  std::vector<SlipEvent> Finish();

 private:
  std::array<bool, kNumLegs> in_stance_{};
  std::array<bool, kNumLegs> open_{};  // a detection in this stance
  std::array<SlipEvent, kNumLegs> current_{};
  std::vector<SlipEvent> events_;
};

struct SlipScoreOptions {
  double match_before_s = 0.02, match_after_s = 0.04;  // scoring.slip_match_*
  double path_length_m = 0;                            // for false detections per metre
};

// Travel bands of slip.recall_by_travel (m): [3, 10), [10, 30), [30, inf) mm.
constexpr std::array<double, 4> kTravelBandEdgesM = {0.003, 0.010, 0.030, std::numeric_limits<double>::infinity()};
constexpr std::array<const char*, 3> kTravelBandNames = {"3_10mm", "10_30mm", "over_30mm"};

struct SlipScore {
  int truth_events = 0, detected_events = 0;
  int true_found = 0, detections_correct = 0;
  double precision = 1, recall = 1;  // 1 when there is nothing to find / nothing detected
  // Per travel band: true events and those found. A true event smaller than the first edge (a
  // threshold set below 3 mm) falls in the first band.
  std::array<int, 3> band_events{}, band_found{};
  double latency_ms_median = std::numeric_limits<double>::quiet_NaN();  // NaN: nothing matched
  double false_per_m = std::numeric_limits<double>::quiet_NaN();        // NaN: no path walked
  double recall_in_band(int b) const {
    return band_events[b] ? static_cast<double>(band_found[b]) / band_events[b] : std::numeric_limits<double>::quiet_NaN();
  }
};

// Marks matched events of both lists and scores them.
SlipScore ScoreSlip(std::vector<SlipEvent>* truth, std::vector<SlipEvent>* detected, const SlipScoreOptions& opt);

// slip.csv: kind (truth|detected), leg, start_s, end_s, crossed_s (truth; empty for
// detections), size (truth: travel m; detection: peak gate statistic), matched.
std::string SlipCsv(const std::vector<SlipEvent>& truth, const std::vector<SlipEvent>& detected);

}  // namespace viqu::runner

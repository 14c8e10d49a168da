#include "runner/slip_score.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace viqu::runner {

void SlipEventBuilder::Add(int64_t t_ns, int64_t period_ns, const std::array<bool, kNumLegs>& on,
                           const std::array<double, kNumLegs>& value) {
  for (int i = 0; i < kNumLegs; ++i) {
    if (on[i]) {
      if (!open_[i]) {
        current_[i] = SlipEvent{i, t_ns, t_ns + period_ns, value[i], false};
        open_[i] = true;
      }
      current_[i].end_ns = t_ns + period_ns;
      current_[i].peak = std::max(current_[i].peak, value[i]);
    } else if (open_[i]) {
      Close(i);
    }
  }
}

void SlipEventBuilder::Close(int leg) {
  open_[leg] = false;
  if (current_[leg].end_ns - current_[leg].start_ns >= min_duration_ns_) events_.push_back(current_[leg]);
}

std::vector<SlipEvent> SlipEventBuilder::Finish() {
  for (int i = 0; i < kNumLegs; ++i) {
    if (open_[i]) Close(i);
  }
  std::sort(events_.begin(), events_.end(),
            [](const SlipEvent& a, const SlipEvent& b) { return a.start_ns < b.start_ns || (a.start_ns == b.start_ns && a.leg < b.leg); });
  return events_;
}

SlipScore ScoreSlip(std::vector<SlipEvent>* truth, std::vector<SlipEvent>* detected, double tolerance_s) {
  const int64_t tol = std::llround(tolerance_s * 1e9);
  for (SlipEvent& t : *truth) t.matched = false;
  for (SlipEvent& d : *detected) d.matched = false;
  for (SlipEvent& t : *truth) {
    for (SlipEvent& d : *detected) {
      if (d.leg != t.leg) continue;
      if (d.start_ns < t.end_ns + tol && t.start_ns < d.end_ns + tol) {
        t.matched = true;
        d.matched = true;
      }
    }
  }
  SlipScore s;
  s.truth_events = static_cast<int>(truth->size());
  s.detected_events = static_cast<int>(detected->size());
  s.true_found = static_cast<int>(std::count_if(truth->begin(), truth->end(), [](const SlipEvent& e) { return e.matched; }));
  s.detections_correct =
      static_cast<int>(std::count_if(detected->begin(), detected->end(), [](const SlipEvent& e) { return e.matched; }));
  s.recall = s.truth_events ? static_cast<double>(s.true_found) / s.truth_events : 1.0;
  s.precision = s.detected_events ? static_cast<double>(s.detections_correct) / s.detected_events : 1.0;
  return s;
}

std::string SlipCsv(const std::vector<SlipEvent>& truth, const std::vector<SlipEvent>& detected) {
  std::string out = "kind,leg,start_s,end_s,peak,matched\n";
  char line[128];
  auto add = [&](const char* kind, const SlipEvent& e) {
    std::snprintf(line, sizeof line, "%s,%s,%.3f,%.3f,%.4g,%d\n", kind, LegName(static_cast<Leg>(e.leg)), e.start_ns * 1e-9,
                  e.end_ns * 1e-9, e.peak, e.matched ? 1 : 0);
    out += line;
  };
  for (const SlipEvent& e : truth) add("truth", e);
  for (const SlipEvent& e : detected) add("detected", e);
  return out;
}

}  // namespace viqu::runner

#include "runner/slip_score.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runner/run_metrics.h"

namespace viqu::runner {
namespace {

bool EarlierStart(const SlipEvent& a, const SlipEvent& b) {
  return a.start_ns < b.start_ns || (a.start_ns == b.start_ns && a.leg < b.leg);
}

}  // namespace

std::vector<SlipEvent> TrueSlipEvents(const std::vector<TrueStance>& stances) {
  std::vector<SlipEvent> out;
  for (const TrueStance& s : stances) {
    if (s.crossed_ns < 0) continue;
    out.push_back(SlipEvent{s.leg, s.touchdown_ns, s.liftoff_ns, s.crossed_ns, s.travel_m, false});
  }
  std::stable_sort(out.begin(), out.end(), EarlierStart);
  return out;
}

void SlipDetectionBuilder::Add(int64_t t_ns, int64_t period_ns, const std::array<bool, kNumLegs>& contact,
                               const std::array<bool, kNumLegs>& flagged, const std::array<double, kNumLegs>& value) {
  for (int i = 0; i < kNumLegs; ++i) {
    if (!contact[i]) {
      // Lift-off closes the stance and its detection.
      if (open_[i]) events_.push_back(current_[i]);
      open_[i] = false;
      in_stance_[i] = false;
      continue;
    }
    in_stance_[i] = true;
    if (!flagged[i]) continue;
    if (!open_[i]) {
      current_[i] = SlipEvent{i, t_ns, t_ns + period_ns, -1, value[i], false};
      open_[i] = true;
    }
    current_[i].end_ns = t_ns + period_ns;
    current_[i].size = std::max(current_[i].size, value[i]);
  }
}

std::vector<SlipEvent> SlipDetectionBuilder::Finish() {
  for (int i = 0; i < kNumLegs; ++i) {
    if (open_[i]) events_.push_back(current_[i]);
    open_[i] = false;
  }
  std::stable_sort(events_.begin(), events_.end(), EarlierStart);
  return events_;
}

SlipScore ScoreSlip(std::vector<SlipEvent>* truth, std::vector<SlipEvent>* detected, const SlipScoreOptions& opt) {
  const int64_t before = std::llround(opt.match_before_s * 1e9), after = std::llround(opt.match_after_s * 1e9);
  for (SlipEvent& t : *truth) t.matched = false;
  for (SlipEvent& d : *detected) d.matched = false;
  std::stable_sort(truth->begin(), truth->end(), EarlierStart);
  std::stable_sort(detected->begin(), detected->end(), EarlierStart);
  std::vector<double> latency_ms;
  for (SlipEvent& d : *detected) {  // by onset
    for (SlipEvent& t : *truth) {   // earliest first
      if (t.matched || t.leg != d.leg) continue;
      if (d.start_ns < t.start_ns - before || d.start_ns > t.end_ns + after) continue;
      t.matched = d.matched = true;
      latency_ms.push_back((d.start_ns - t.crossed_ns) * 1e-6);
      break;
    }
  }
  SlipScore s;
  s.truth_events = static_cast<int>(truth->size());
  s.detected_events = static_cast<int>(detected->size());
  for (const SlipEvent& t : *truth) {
    int band = 0;
    while (band < 2 && t.size >= kTravelBandEdgesM[band + 1]) ++band;
    ++s.band_events[band];
    if (t.matched) {
      ++s.true_found;
      ++s.band_found[band];
    }
  }
  s.detections_correct =
      static_cast<int>(std::count_if(detected->begin(), detected->end(), [](const SlipEvent& e) { return e.matched; }));
  if (s.truth_events) s.recall = static_cast<double>(s.true_found) / s.truth_events;
  if (s.detected_events) s.precision = static_cast<double>(s.detections_correct) / s.detected_events;
  s.latency_ms_median = Median(latency_ms);
  if (opt.path_length_m > 0) s.false_per_m = (s.detected_events - s.detections_correct) / opt.path_length_m;
  return s;
}

std::string SlipCsv(const std::vector<SlipEvent>& truth, const std::vector<SlipEvent>& detected) {
  std::string out = "kind,leg,start_s,end_s,crossed_s,size,matched\n";
  char line[160];
  auto add = [&](const char* kind, const SlipEvent& e) {
    char crossed[32] = "";
    if (e.crossed_ns >= 0) std::snprintf(crossed, sizeof crossed, "%.3f", e.crossed_ns * 1e-9);
    std::snprintf(line, sizeof line, "%s,%s,%.3f,%.3f,%s,%.4g,%d\n", kind, LegName(static_cast<Leg>(e.leg)),
                  e.start_ns * 1e-9, e.end_ns * 1e-9, crossed, e.size, e.matched ? 1 : 0);
    out += line;
  };
  for (const SlipEvent& e : truth) add("truth", e);
  for (const SlipEvent& e : detected) add("detected", e);
  return out;
}

}  // namespace viqu::runner

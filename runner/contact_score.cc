#include "runner/contact_score.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runner/run_metrics.h"

namespace viqu::runner {

void ContactScorer::Add(int64_t t_ns, const std::array<bool, kNumLegs>& estimated, const std::array<bool, kNumLegs>& truth) {
  for (int i = 0; i < kNumLegs; ++i) {
    ++samples_;
    agree_ += estimated[i] == truth[i];
    if (have_last_ && estimated[i] != last_[i]) estimated_.push_back(Transition{i, estimated[i], t_ns});
  }
  last_ = estimated;
  have_last_ = true;
}

void ContactScorer::AddForce(const std::array<double, kNumLegs>& est_normal_n, const std::array<bool, kNumLegs>& truth,
                             const std::array<double, kNumLegs>& true_normal_n) {
  for (int i = 0; i < kNumLegs; ++i) {
    if (!truth[i] || !std::isfinite(est_normal_n[i])) continue;
    const double e = est_normal_n[i] - true_normal_n[i];
    force_sq_ += e * e;
    force_sum_ += true_normal_n[i];
    ++force_samples_;
  }
}

ContactScore ContactScorer::Finish(const std::vector<TrueStance>& stances, std::string* csv) {
  ContactScore s;
  s.samples = samples_;
  if (samples_) s.accuracy = static_cast<double>(agree_) / samples_;
  s.force_samples = force_samples_;
  if (force_samples_) {
    s.normal_rmse_n = std::sqrt(force_sq_ / force_samples_);
    s.true_normal_mean_n = force_sum_ / force_samples_;
  }
  const int64_t window = std::llround(kTransitionMatchS * 1e9);
  std::vector<double> td_err, lo_err;
  *csv = "leg,kind,true_s,estimated_s,error_ms\n";
  char line[128];
  const auto pair = [&](int leg, bool touchdown, int64_t t_true) {
    const Transition* best = nullptr;
    for (const Transition& e : estimated_) {
      if (e.leg != leg || e.touchdown != touchdown || std::llabs(e.t_ns - t_true) > window) continue;
      if (!best || std::llabs(e.t_ns - t_true) < std::llabs(best->t_ns - t_true)) best = &e;
    }
    if (best) {
      const double err_ms = (best->t_ns - t_true) * 1e-6;
      (touchdown ? td_err : lo_err).push_back(std::abs(err_ms));
      std::snprintf(line, sizeof line, "%s,%s,%.3f,%.3f,%.1f\n", LegName(static_cast<Leg>(leg)),
                    touchdown ? "touchdown" : "liftoff", t_true * 1e-9, best->t_ns * 1e-9, err_ms);
    } else {
      std::snprintf(line, sizeof line, "%s,%s,%.3f,,\n", LegName(static_cast<Leg>(leg)),
                    touchdown ? "touchdown" : "liftoff", t_true * 1e-9);
    }
    *csv += line;
    return best != nullptr;
  };
  for (const TrueStance& st : stances) {
    if (!st.from_start) {
      ++s.touchdowns;
      s.touchdowns_paired += pair(st.leg, true, st.touchdown_ns);
    }
    if (!st.to_end) {
      ++s.liftoffs;
      s.liftoffs_paired += pair(st.leg, false, st.liftoff_ns);
    }
  }
  s.touchdown_err_ms_median = Median(td_err);
  s.liftoff_err_ms_median = Median(lo_err);
  return s;
}

}  // namespace viqu::runner

#include "runner/foot_truth.h"

#include <algorithm>
#include <cmath>

namespace viqu::runner {

void FootTruth::Step(int64_t t_ns, double dt_s, const std::array<bool, kNumLegs>& raw_contact,
                     const std::array<Eigen::Vector3d, kNumLegs>& sole_velocity_w) {
  // The debounce in whole physics steps, at least one.
  const int debounce_steps = dt_s > 0 ? std::max(1, static_cast<int>(std::lround(debounce_s_ / dt_s))) : 1;
  if (!started_) {
    // The feet down at the run's start are in stance from it, with no touch-down of their own.
    started_ = true;
    for (int i = 0; i < kNumLegs; ++i) {
      contact_[i] = raw_contact[i];
      travel_[i].setZero();
      if (contact_[i]) open_[i] = TrueStance{i, t_ns, t_ns, 0.0, -1, 0.0, true, false};
    }
  }
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::Vector2d v = sole_velocity_w[i].head<2>();
    const Eigen::Vector2d step = v * dt_s;
    bool in_stance = false;  // this step counts towards an open stance's travel
    if (raw_contact[i] == contact_[i]) {
      // A change that did not hold: a lift-off that came back down keeps its travel (the foot was
      // on the ground but for a bounce), a touch that did not hold is forgotten.
      if (differing_[i] > 0 && contact_[i]) {
        travel_[i] += pending_[i];
        open_[i].peak_speed_mps = std::max(open_[i].peak_speed_mps, pending_peak_[i]);
      }
      differing_[i] = 0;
      pending_[i].setZero();
      pending_peak_[i] = 0;
      if (contact_[i]) {
        travel_[i] += step;
        in_stance = true;
      }
    } else {
      if (differing_[i] == 0) differ_since_ns_[i] = t_ns;
      ++differing_[i];
      pending_[i] += step;
      pending_peak_[i] = std::max(pending_peak_[i], v.norm());
      if (differing_[i] >= debounce_steps) {
        if (raw_contact[i]) {
          contact_[i] = true;
          open_[i] = TrueStance{i, differ_since_ns_[i], differ_since_ns_[i], 0.0, -1, pending_peak_[i], false, false};
          travel_[i] = pending_[i];
          in_stance = true;
        } else {
          Close(i, differ_since_ns_[i]);
          contact_[i] = false;
          travel_[i].setZero();
        }
        differing_[i] = 0;
        pending_[i].setZero();
        pending_peak_[i] = 0;
      }
    }
    if (!in_stance) continue;
    TrueStance& st = open_[i];
    st.peak_speed_mps = std::max(st.peak_speed_mps, v.norm());
    const double d = travel_[i].norm();
    st.travel_m = std::max(st.travel_m, d);
    if (st.crossed_ns < 0 && d > slip_travel_m_) st.crossed_ns = t_ns;
  }
}

void FootTruth::Close(int leg, int64_t t_ns) {
  open_[leg].liftoff_ns = t_ns;
  stances_.push_back(open_[leg]);
}

std::vector<TrueStance> FootTruth::Finish(int64_t t_end_ns) {
  for (int i = 0; i < kNumLegs; ++i) {
    if (contact_[i]) {
      open_[i].to_end = true;
      Close(i, t_end_ns);
      contact_[i] = false;
    }
  }
  std::stable_sort(stances_.begin(), stances_.end(), [](const TrueStance& a, const TrueStance& b) {
    return a.touchdown_ns < b.touchdown_ns || (a.touchdown_ns == b.touchdown_ns && a.leg < b.leg);
  });
  return stances_;
}

}  // namespace viqu::runner

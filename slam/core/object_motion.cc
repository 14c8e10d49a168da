#include "slam/core/object_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slam/core/map.h"

namespace viqu::slam {
namespace {

constexpr double kMatchRatio = 0.8;      // best / second-best Hamming distance (Lowe's test)
constexpr double kMedianEfficiency = 1.2533;  // std error of a median = sqrt(pi/2) * sigma / sqrt(n)

double Median(std::vector<double> v) {
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  double m = v[mid];
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<long>(mid)));
  return m;
}

// Best and second-best distance from row i of `a` to the rows of `b` (those with `usable_b` set,
// when it is not empty); index of the best.
int BestMatch(const cv::Mat& a, int i, const cv::Mat& b, const std::vector<bool>& usable_b, int* best_d, int* second_d) {
  int best = -1;
  *best_d = *second_d = std::numeric_limits<int>::max();
  for (int j = 0; j < b.rows; ++j) {
    if (!usable_b.empty() && !usable_b[static_cast<size_t>(j)]) continue;
    const int d = DescriptorDistance(a.ptr<uint8_t>(i), b.ptr<uint8_t>(j));
    if (d < *best_d) {
      *second_d = *best_d;
      *best_d = d;
      best = j;
    } else if (d < *second_d) {
      *second_d = d;
    }
  }
  return best;
}

}  // namespace

MotionMeasurement MeasureMotion(const ObjectSnapshot& ref, const ObjectSnapshot& cur, const AdaptiveDynamicSettings& s,
                                const InViewIfStatic& in_view) {
  MotionMeasurement m;
  m.lag_s = (cur.t_ns - ref.t_ns) * 1e-9;
  if (ref.size() == 0 || cur.size() == 0) return m;
  std::vector<bool> usable;
  if (in_view) {
    usable.resize(ref.size());
    for (size_t j = 0; j < ref.size(); ++j) usable[j] = in_view(ref.p_w[j]);
  }
  std::vector<double> dx, dy, dz, sigma;
  for (int i = 0; i < cur.descriptors.rows; ++i) {
    int best_d, second_d;
    const int j = BestMatch(cur.descriptors, i, ref.descriptors, usable, &best_d, &second_d);
    if (j < 0 || best_d > s.max_hamming || best_d >= kMatchRatio * second_d) continue;
    int back_d, back_second;
    if (BestMatch(ref.descriptors, j, cur.descriptors, {}, &back_d, &back_second) != i) continue;
    const Eigen::Vector3d d = cur.p_w[static_cast<size_t>(i)] - ref.p_w[static_cast<size_t>(j)];
    dx.push_back(d.x());
    dy.push_back(d.y());
    dz.push_back(d.z());
    sigma.push_back(std::hypot(cur.sigma_m[static_cast<size_t>(i)], ref.sigma_m[static_cast<size_t>(j)]));
  }
  m.matches = static_cast<int>(dx.size());
  if (m.matches < s.min_matches) return m;
  m.judged = true;
  m.displacement_w = {Median(dx), Median(dy), Median(dz)};
  m.displacement_m = m.displacement_w.norm();
  m.std_error_m = kMedianEfficiency * Median(sigma) / std::sqrt(static_cast<double>(m.matches));
  m.threshold_m = s.threshold_m + s.k_sigma * m.std_error_m;
  m.moving = m.displacement_m > m.threshold_m;
  // Stillness needs a long look: a walking person's stance foot stands still between two frames
  // while the other swings, so a short lag can show motion but never rule it out. Half the lag
  // (not a setting: it only says "a long look", lag_s sets the scale).
  m.still = !m.moving && m.displacement_m + s.k_sigma * m.std_error_m < s.still_max_m && m.lag_s >= 0.5 * s.lag_s;
  return m;
}

bool ObjectMotionTrack::Add(ObjectSnapshot snapshot, const AdaptiveDynamicSettings& s, const InViewIfStatic& in_view) {
  const int64_t t_ns = snapshot.t_ns;
  const int64_t lag_ns = static_cast<int64_t>(s.lag_s * 1e9);
  while (!history_.empty() && history_.front().t_ns < t_ns - lag_ns) history_.pop_front();
  // Against the oldest snapshot within the lag (the longest baseline in time, for slow objects);
  // when it gives too few matches (a walking person's legs change their look), the middle one,
  // then the previous frame. Three at most bounds the cost per frame.
  last_ = MotionMeasurement();
  std::vector<const ObjectSnapshot*> refs;
  for (const ObjectSnapshot& ref : history_) {
    if (ref.size() > 0) refs.push_back(&ref);
  }
  if (!refs.empty()) {
    const size_t picks[] = {0, refs.size() / 2, refs.size() - 1};
    for (size_t k = 0; k < 3; ++k) {
      if (k > 0 && picks[k] == picks[k - 1]) continue;
      last_ = MeasureMotion(*refs[picks[k]], snapshot, s, in_view);
      if (last_.judged) break;
    }
  }
  consecutive_moving_ = last_.moving ? consecutive_moving_ + 1 : 0;
  // Onset needs confirm_frames judgements of motion in a row; once dynamic, every one counts.
  if (last_.moving && (dynamic_ || consecutive_moving_ >= s.confirm_frames)) {
    last_motion_ns_ = t_ns;
    moved_ = true;
    static_since_motion_ = false;
  } else if (last_.still && moved_) {
    static_since_motion_ = true;
  }
  // Released only after hold_s and a judgement that it stands still: an object that moved and
  // then cannot be judged (too few matches, too far for stereo to rule motion out) stays dynamic.
  dynamic_ = moved_ && (t_ns - last_motion_ns_ <= static_cast<int64_t>(s.hold_s * 1e9) || !static_since_motion_);
  history_.push_back(std::move(snapshot));
  return dynamic_;
}

}  // namespace viqu::slam

#include "slam/core/object_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "slam/core/map.h"
#include "slam/core/median.h"

namespace viqu::slam {
namespace {

constexpr double kMatchRatio = 0.8;      // best / second-best Hamming distance (Lowe's test)

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
  std::vector<bool> usable_ref, usable_cur;
  if (in_view) {
    usable_ref.resize(ref.size());
    for (size_t j = 0; j < ref.size(); ++j) usable_ref[j] = in_view(cur.T_c_w, ref.p_w[j]);
    usable_cur.resize(cur.size());
    for (size_t i = 0; i < cur.size(); ++i) usable_cur[i] = in_view(ref.T_c_w, cur.p_w[i]);
  }
  const bool isotropic = cur.sigma_lateral_m.empty() || ref.sigma_lateral_m.empty();
  std::vector<Eigen::Vector3d> d, ray;
  std::vector<double> var_along, var_across;
  const Eigen::Vector3d camera_w = cur.T_c_w.inverse().translation();
  for (int i = 0; i < cur.descriptors.rows; ++i) {
    if (!usable_cur.empty() && !usable_cur[static_cast<size_t>(i)]) continue;
    int best_d, second_d;
    const int j = BestMatch(cur.descriptors, i, ref.descriptors, usable_ref, &best_d, &second_d);
    if (j < 0 || best_d > s.max_hamming || best_d >= kMatchRatio * second_d) continue;
    int back_d, back_second;
    if (BestMatch(ref.descriptors, j, cur.descriptors, usable_cur, &back_d, &back_second) != i) continue;
    const size_t ci = static_cast<size_t>(i), rj = static_cast<size_t>(j);
    d.push_back(cur.p_w[ci] - ref.p_w[rj]);
    // The ref point's ray differs from the current one by the robot's motion over the lag (a few
    // degrees at the distances where depth exists): both errors are taken along the current ray.
    ray.push_back((cur.p_w[ci] - camera_w).normalized());
    var_along.push_back(cur.sigma_m[ci] * cur.sigma_m[ci] + ref.sigma_m[rj] * ref.sigma_m[rj]);
    var_across.push_back(isotropic ? var_along.back()
                                   : cur.sigma_lateral_m[ci] * cur.sigma_lateral_m[ci] +
                                         ref.sigma_lateral_m[rj] * ref.sigma_lateral_m[rj]);
  }
  m.matches = static_cast<int>(d.size());
  if (m.matches < s.min_matches) return m;
  m.judged = true;
  // Axes: the object's mean viewing ray and two directions across it.
  Eigen::Vector3d along = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& r : ray) along += r;
  along = along.norm() > 0 ? along.normalized() : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d helper = Eigen::Vector3d::Zero();
  Eigen::Index smallest;
  along.cwiseAbs().minCoeff(&smallest);
  helper(smallest) = 1;
  const Eigen::Vector3d across1 = along.cross(helper).normalized(), across2 = along.cross(across1);
  const Eigen::Vector3d axes[3] = {along, across1, across2};
  const double root_n = std::sqrt(static_cast<double>(m.matches));
  Eigen::Vector3d median, excess, upper;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> comp(d.size()), sigma(d.size());
    for (size_t i = 0; i < d.size(); ++i) {
      comp[i] = d[i].dot(axes[k]);
      // A point's error lies along its own ray (depth) and across it (position): its share on
      // this axis. Off the mean ray, part of the large depth error falls across.
      const double c2 = std::min(1.0, ray[i].dot(axes[k]) * ray[i].dot(axes[k]));
      sigma[i] = std::sqrt(var_along[i] * c2 + var_across[i] * (1 - c2));
    }
    median(k) = Median(comp);
    m.std_error(k) = kMedianEfficiency * Median(sigma) / root_n;
    excess(k) = std::max(0.0, std::abs(median(k)) - s.k_sigma * m.std_error(k));
    upper(k) = std::abs(median(k)) + s.k_sigma * m.std_error(k);
  }
  if (m.lag_s > 0 && median.norm() - s.k_sigma * m.std_error.norm() > s.max_speed_mps * m.lag_s) {
    m.judged = false;  // faster than any object followed here: mismatches
    m.too_fast = true;
    return m;
  }
  m.displacement_w = median(0) * axes[0] + median(1) * axes[1] + median(2) * axes[2];
  m.displacement_m = median.norm();
  m.threshold_m = s.threshold_m + (m.displacement_m - excess.norm());
  m.moving = excess.norm() > s.threshold_m;
  // Stillness needs a long look: a walking person's stance foot stands still between two frames
  // while the other swings, so a short lag can show motion but never rule it out. Half the lag
  // (not a setting: it only says "a long look", lag_s sets the scale).
  m.still = !m.moving && upper.norm() < s.still_max_m && m.lag_s >= 0.5 * s.lag_s;
  return m;
}

void ObjectMotionTrack::LookAtSilhouette(const ObjectSnapshot& snapshot, const AdaptiveDynamicSettings& s,
                                         const StereoCamera* cam) {
  if (cam == nullptr || !(s.silhouette_threshold_m > 0) || !(snapshot.depth_m > 0) || snapshot.silhouette.empty()) return;
  // The earlier snapshot nearest silhouette_lag_s back, with a silhouette and a depth.
  const int64_t want_ns = snapshot.t_ns - static_cast<int64_t>(s.silhouette_lag_s * 1e9);
  const ObjectSnapshot* ref = nullptr;
  for (const Past& p : history_) {
    const ObjectSnapshot& r = p.snapshot;
    if (r.t_ns >= snapshot.t_ns || r.silhouette.empty() || !(r.depth_m > 0)) continue;
    if (ref == nullptr || std::llabs(r.t_ns - want_ns) < std::llabs(ref->t_ns - want_ns)) ref = &r;
  }
  if (ref == nullptr) return;
  const SilhouetteShift shift =
      MeasureSilhouetteShift(ref->silhouette, ref->depth_m, snapshot.silhouette, *cam, s.silhouette_min_rows);
  if (shift.rows == 0) return;
  // One side alone cannot tell motion from the mask's growth.
  const double growth_px = shift.two_sided ? 0.0 : s.silhouette_growth_px;
  const double m_per_px = snapshot.depth_m / cam->fx;
  const double excess_m = (std::abs(shift.shift_px) - s.k_sigma * shift.std_error_px - growth_px) * m_per_px;
  if (excess_m <= s.silhouette_threshold_m) return;
  last_.moving = true;
  last_.judged = true;
  last_.still = false;
  last_.by_silhouette = true;
  last_.silhouette_m = excess_m;
  last_.lag_s = (snapshot.t_ns - ref->t_ns) * 1e-9;
}

int64_t ObjectMotionTrack::UnmovedUntilNs(int64_t t_ns) const {
  // Both looks compare the object with where it stood up to lag_s earlier, so after the onset t0
  // their displacements grow as v (t - t0): the line through the still look's (t_s, d_s) and this
  // look of motion's (t, d) meets zero at t0 = t_s - d_s (t - t_s) / (d - d_s). The still look's
  // displacement is at least its noise (a norm), which moves t0 earlier, never later. Without it
  // the date is t_s, by which a crate at 0.1 m/s has moved up to 1.5 cm (the still look allows up
  // to stop_max_m, and its displacement is measured with the tracked pose that the object drags
  // along): keyframes of that stretch kept their observations of a box that had moved.
  if (last_unmoved_ns_ <= 0 || !last_.moving || t_ns <= last_unmoved_ns_ || last_.displacement_m <= last_unmoved_m_) {
    return last_unmoved_ns_;
  }
  // Clamped to the still look's span before the cast: a look of motion by the silhouette may
  // carry a displacement barely above the still look's, which would send the line far back.
  const double span_ns = static_cast<double>(last_unmoved_ns_ - last_unmoved_ref_ns_);
  const double back_ns = std::min(
      span_ns, last_unmoved_m_ * static_cast<double>(t_ns - last_unmoved_ns_) / (last_.displacement_m - last_unmoved_m_));
  return last_unmoved_ns_ - static_cast<int64_t>(back_ns);
}

void ObjectMotionTrack::RestartMeasurements() {
  history_.clear();
  consecutive_moving_ = 0;
}

bool ObjectMotionTrack::Add(ObjectSnapshot snapshot, const AdaptiveDynamicSettings& s, const InViewIfStatic& in_view,
                            const StereoCamera* cam) {
  const int64_t t_ns = snapshot.t_ns;
  const int64_t lag_ns = static_cast<int64_t>(s.lag_s * 1e9);
  while (!history_.empty() && history_.front().snapshot.t_ns < t_ns - lag_ns) history_.pop_front();
  // Against the oldest snapshot within the lag (the longest baseline in time, for slow objects);
  // when it gives too few matches (a walking person's legs change their look), the one nearest
  // half that lag ago, a quarter, and so on down to the previous frame: a walker who has just
  // set off has moved 10-20 cm a quarter of a second ago, and still looks enough like that to
  // match, where a second ago its legs stood elsewhere and the previous frame shows only 2-4 cm.
  // Halving bounds the cost per frame by log2 of the frames in lag_s.
  last_ = MotionMeasurement();
  std::vector<Past*> refs;
  for (Past& ref : history_) {
    if (ref.snapshot.size() > 0) refs.push_back(&ref);
  }
  // Over a long lag a transient jump (a frame whose mask held the background behind the object, a
  // stereo mismatch of its depth) is slow enough to pass for motion; against the next frame it is
  // faster than any object. A look that sees motion is therefore checked: a reference that jumps
  // from the snapshot after it is skipped, and a current snapshot that jumps from the previous
  // frame is a mismatch, not motion. Only looks that see motion, of an object not yet dynamic,
  // are checked (each check is one more matching: a moving crate of 256 features tripled the
  // stage's cost): once dynamic, a mismatch can only lengthen the hold.
  const auto jumps_to_next = [&](size_t i) {
    if (refs[i]->jumps_to_next < 0) {
      refs[i]->jumps_to_next = MeasureMotion(refs[i]->snapshot, refs[i + 1]->snapshot, s, in_view).too_fast;
    }
    return refs[i]->jumps_to_next == 1;
  };
  size_t tried = refs.size();
  for (double back_s = s.lag_s; !refs.empty(); back_s *= 0.5) {
    // The snapshot nearest back_s before this one; the previous frame ends the chain.
    const int64_t want_ns = t_ns - static_cast<int64_t>(back_s * 1e9);
    size_t i = refs.size() - 1;
    for (size_t k = 0; k < refs.size(); ++k) {
      if (std::llabs(refs[k]->snapshot.t_ns - want_ns) < std::llabs(refs[i]->snapshot.t_ns - want_ns)) i = k;
    }
    if (i != tried) {
      tried = i;
      MotionMeasurement m = MeasureMotion(refs[i]->snapshot, snapshot, s, in_view);
      if (!(m.moving && !dynamic_ && i + 1 < refs.size() && jumps_to_next(i))) {
        last_ = m;
        if (last_.judged) break;
      }
    }
    if (i + 1 == refs.size()) break;
  }
  if (last_.moving && !dynamic_ && tried + 1 < refs.size()) {
    const MotionMeasurement step = MeasureMotion(refs.back()->snapshot, snapshot, s, in_view);
    if (step.too_fast) last_ = step;
  }
  if (!last_.moving && !dynamic_) LookAtSilhouette(snapshot, s, cam);
  consecutive_moving_ = last_.moving ? consecutive_moving_ + 1 : 0;
  // A judgement spans [t - lag, t]: the motion it sees happened somewhere in that span.
  const int64_t ref_ns = t_ns - static_cast<int64_t>(last_.lag_s * 1e9);
  // Onset needs confirm_frames judgements of motion in a row; once dynamic, or within hold_s of its
  // release (a walker who paused and walks on), every one counts.
  const bool recently_dynamic = released_ns_ >= 0 && t_ns - released_ns_ <= static_cast<int64_t>(s.hold_s * 1e9);
  // Within hold_s of a release, changed_look_frames looks in a row that cannot be judged although
  // the object has enough features with depth count as motion: an object that just stood still
  // matched itself well (that is how it was released), and a walker who walks on changes its look
  // (legs swinging, their patches mostly background at a distance) so that nothing matches.
  const bool unmatched = !last_.judged && snapshot.size() >= static_cast<size_t>(s.min_matches);
  unjudged_after_release_ = recently_dynamic && !dynamic_ && unmatched ? unjudged_after_release_ + 1 : 0;
  const bool changed_look = s.changed_look_frames > 0 && unjudged_after_release_ >= s.changed_look_frames;
  // A look of motion by the silhouette alone drops the object's features (tentatively) but does
  // not confirm it: a mask is one detector's word, and the confirmation culls map points and holds
  // the object; confirming by the mask made the standing_crowd run's keyframes fall on a trot's
  // jolt, which then tracked 65 mm off (docs/MEASURED.md, session 22).
  const bool confirms = !last_.by_silhouette;
  if (last_.moving) run_start_ns_ = consecutive_moving_ == 1 ? ref_ns : std::min(run_start_ns_, ref_ns);
  if (changed_look ||
      (last_.moving && (dynamic_ || recently_dynamic || (confirms && consecutive_moving_ >= s.confirm_frames)))) {
    if (!dynamic_) {
      motion_onset_ns_ = std::max(UnmovedUntilNs(t_ns), changed_look && !last_.moving ? t_ns - lag_ns : run_start_ns_);
    }
    last_motion_ns_ = t_ns;
    last_motion_ref_ns_ = ref_ns;
    moved_ = true;
    static_since_motion_ = false;
  } else if (last_.still && moved_) {
    static_since_motion_ = true;
    // A still look that starts after the last motion's look started and whose median displacement
    // is below stop_max_m dates that motion no later than its own start: the hold runs from there.
    // Without this an object that stopped is held for up to lag_s longer than it moved (the last
    // look that still reached back into its walk ends up to lag_s after the stop). A look merely
    // not judged moving may hide nearly threshold_m of slow motion (a crate at 0.1 m/s: 0.2 s of
    // it), so it dates nothing.
    if (ref_ns > last_motion_ref_ns_ && last_.displacement_m < s.stop_max_m) {
      last_motion_ns_ = std::min(last_motion_ns_, ref_ns);
    }
  }
  // Released only after hold_s and a judgement that it stands still: an object that moved and
  // then cannot be judged (too few matches, too far for stereo to rule motion out) stays dynamic.
  if (last_.still && last_.displacement_m < s.stop_max_m) {
    last_unmoved_ns_ = t_ns;
    last_unmoved_ref_ns_ = ref_ns;
    last_unmoved_m_ = last_.displacement_m;
  }
  const bool was_dynamic = dynamic_;
  dynamic_ = moved_ && (t_ns - last_motion_ns_ <= static_cast<int64_t>(s.hold_s * 1e9) || !static_since_motion_);
  if (was_dynamic && !dynamic_) released_ns_ = t_ns;
  history_.push_back(Past{std::move(snapshot)});
  const bool tentative = last_.moving && consecutive_moving_ >= s.drop_frames;
  return dynamic_ || tentative;
}

}  // namespace viqu::slam

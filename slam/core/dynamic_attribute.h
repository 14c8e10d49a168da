#pragma once
// The paper's dynamic attribute (ViQu-SLAM, Section III-B, eqs. 1-4), written as it stands, for
// `dynamic.method: paper`:
//   eq. 1  D_mean(k) = mean stereo depth of the features inside object k's mask;
//   eq. 2  [dw, dd] = mean over the second half of the window S of [w_bar, d_bar] minus the mean
//          over its first half, where w_bar is the mean norm of the world positions of the map
//          points labelled k (their projection falls in k's mask, paper Fig. 2) and d_bar is eq. 1;
//   eq. 3  A_k = alpha * dw + beta * dd + gamma * Pr_k;
//   eq. 4  dA = the same half-window difference over the last N values of A; k is dynamic when
//          dA > th_d.
// Two readings were needed: the paper's sums of eqs. 2 and 4 share the index S/2-1 (a typo for two
// disjoint halves; here the halves are the first and last floor(n/2) entries), and the window S
// is taken in seconds (`window_s`). Known weaknesses, kept on purpose because this is the
// literal form: the constant prior cancels in eq. 4; eq. 4 differences a difference, so an object
// moving at constant speed gives dA near 0; the norm of world positions ignores motion on a
// sphere about the origin; there is no absolute value, so an object coming closer is never
// dynamic. `adaptive` (object_motion.h) is the well-posed variant.
#include <cstdint>
#include <deque>
#include <vector>

#include "slam/measurements/stereo_frame.h"
#include "slam/settings/slam_settings.h"

namespace viqu::slam {

// Eq. 1: the mean of the positive depths (m); 0 when there is none.
double MeanMaskDepth(const std::vector<float>& feature_depths_m);

// The mean of the last floor(n/2) values minus the mean of the first floor(n/2) (eqs. 2 and 4);
// 0 for fewer than two values.
double HalfWindowChange(const std::vector<double>& values);

// Eq. 3.
double DynamicAttribute(double dw_m, double dd_m, double prior, double alpha, double beta, double gamma);

// Pr_k of the category (0 for categories that are not movable).
double CategoryPrior(Category c, const CategoryPriors& p);

// The state of eqs. 2-4 for one object over time.
class PaperAttributeSeries {
 public:
  // Adds one frame's w_bar (mean norm of labelled map points, m) and d_bar (eq. 1, m) and returns
  // whether the object is dynamic after it. A frame with no labelled point or no depth is skipped
  // (returns the last decision).
  bool Add(int64_t t_ns, double w_bar_m, double d_bar_m, double prior, const DynamicSettings& s);
  double last_delta_a() const { return last_delta_a_; }  // eq. 4 of the last frame (m)

 private:
  struct Entry {
    int64_t t_ns;
    double w_bar, d_bar;
  };
  std::deque<Entry> window_;     // eq. 2: the entries of the last window_s
  std::deque<double> a_values_;  // eq. 4: the last window_n values of A
  double last_delta_a_ = 0;
  bool dynamic_ = false;
};

}  // namespace viqu::slam

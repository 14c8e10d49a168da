#include "slam/core/dynamic_attribute.h"

namespace viqu::slam {

double MeanMaskDepth(const std::vector<float>& feature_depths_m) {
  double sum = 0;
  int n = 0;
  for (float d : feature_depths_m) {
    if (d > 0) {
      sum += d;
      ++n;
    }
  }
  return n > 0 ? sum / n : 0.0;
}

double HalfWindowChange(const std::vector<double>& values) {
  const size_t half = values.size() / 2;
  if (half == 0) return 0.0;
  double first = 0, second = 0;
  for (size_t i = 0; i < half; ++i) {
    first += values[i];
    second += values[values.size() - half + i];
  }
  return (second - first) / static_cast<double>(half);
}

double DynamicAttribute(double dw_m, double dd_m, double prior, double alpha, double beta, double gamma) {
  return alpha * dw_m + beta * dd_m + gamma * prior;
}

double CategoryPrior(Category c, const CategoryPriors& p) {
  switch (c) {
    case Category::kPerson: return p.person;
    case Category::kBox: return p.box;
    case Category::kBall: return p.ball;
    default: return 0.0;
  }
}

bool PaperAttributeSeries::Add(int64_t t_ns, double w_bar_m, double d_bar_m, double prior, const DynamicSettings& s) {
  if (!(w_bar_m > 0) || !(d_bar_m > 0)) return dynamic_;
  window_.push_back({t_ns, w_bar_m, d_bar_m});
  const int64_t window_ns = static_cast<int64_t>(s.window_s * 1e9);
  while (!window_.empty() && window_.front().t_ns < t_ns - window_ns) window_.pop_front();
  std::vector<double> w, d;
  for (const Entry& e : window_) {
    w.push_back(e.w_bar);
    d.push_back(e.d_bar);
  }
  if (w.size() < 2) return dynamic_;
  a_values_.push_back(DynamicAttribute(HalfWindowChange(w), HalfWindowChange(d), prior, s.alpha, s.beta, s.gamma));
  while (a_values_.size() > static_cast<size_t>(s.window_n)) a_values_.pop_front();
  if (a_values_.size() < static_cast<size_t>(s.window_n)) return dynamic_;
  last_delta_a_ = HalfWindowChange(std::vector<double>(a_values_.begin(), a_values_.end()));
  dynamic_ = last_delta_a_ > s.th_d;
  return dynamic_;
}

}  // namespace viqu::slam

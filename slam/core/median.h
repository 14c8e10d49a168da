#pragma once
// The median of a sample, and the constant that turns a sample's spread into the standard error
// of its median.
#include <algorithm>
#include <vector>

namespace viqu::slam {

// Standard error of a median of n draws from a normal distribution: sqrt(pi / 2) * sigma / sqrt(n).
constexpr double kMedianEfficiency = 1.2533;

// The middle value (the mean of the two middle values for an even count); `v` must not be empty.
inline double Median(std::vector<double> v) {
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  double m = v[mid];
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<long>(mid)));
  return m;
}

}  // namespace viqu::slam

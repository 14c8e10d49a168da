#include "sim/depth_quantisation.h"

#include <cmath>
#include <cstdint>

#include "common/errors.h"

namespace viqu::sim {

cv::Mat DepthToSteps(const cv::Mat& depth_m, double steps_per_m) {
  if (depth_m.type() != CV_32F) throw RunError("depth must be CV_32F (m)");
  cv::Mat steps(depth_m.size(), CV_16U);
  for (int r = 0; r < steps.rows; ++r) {
    const float* src = depth_m.ptr<float>(r);
    uint16_t* dst = steps.ptr<uint16_t>(r);
    for (int c = 0; c < steps.cols; ++c) {
      const double v = std::round(static_cast<double>(src[c]) * steps_per_m);
      dst[c] = (std::isfinite(v) && v > 0 && v <= 65535) ? static_cast<uint16_t>(v) : 0;
    }
  }
  return steps;
}

void QuantiseDepth(cv::Mat* depth_m, double steps_per_m) {
  if (!depth_m || depth_m->empty()) return;
  DepthToSteps(*depth_m, steps_per_m).convertTo(*depth_m, CV_32F, 1.0 / steps_per_m);
}

}  // namespace viqu::sim

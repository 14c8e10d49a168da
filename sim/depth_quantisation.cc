#include "sim/depth_quantisation.h"

#include <cstdint>
#include <string>

#include "common/errors.h"

namespace viqu::sim {

cv::Mat DepthToSteps(const cv::Mat& depth_m, double steps_per_m) {
  if (depth_m.type() != CV_32F) throw RunError("depth must be CV_32F (m)");
  cv::Mat steps(depth_m.size(), CV_16U);
  for (int r = 0; r < steps.rows; ++r) {
    const float* src = depth_m.ptr<float>(r);
    uint16_t* dst = steps.ptr<uint16_t>(r);
    for (int c = 0; c < steps.cols; ++c) {
      // std::round (halves away from zero) without a library call: v - trunc(v) is exact for
      // these magnitudes. round(v) lies in [1, 65535] exactly when v is in [0.5, 65535.5); NaN
      // fails both tests, so non-finite, non-positive and out-of-range depth give 0.
      const double v = static_cast<double>(src[c]) * steps_per_m;
      uint16_t out = 0;
      if (v >= 0.5 && v < 65535.5) {
        const int32_t whole = static_cast<int32_t>(v);
        out = static_cast<uint16_t>(whole + (v - whole >= 0.5 ? 1 : 0));
      }
      dst[c] = out;
    }
  }
  return steps;
}

cv::Mat QuantiseDepth(cv::Mat* depth_m, double steps_per_m) {
  if (!depth_m || depth_m->empty()) return cv::Mat();
  cv::Mat steps = DepthToSteps(*depth_m, steps_per_m);
  steps.convertTo(*depth_m, CV_32F, 1.0 / steps_per_m);
  return steps;
}

cv::Mat DepthStepsToWrite(const cv::Mat& depth_m, const cv::Mat& given, double steps_per_m, const char* who) {
  if (given.empty()) return DepthToSteps(depth_m, steps_per_m);
  if (given.type() != CV_16U || given.size() != depth_m.size()) {
    throw RunError(std::string(who) + ": depth steps must be CV_16U and the size of the depth image");
  }
  return given;
}

}  // namespace viqu::sim

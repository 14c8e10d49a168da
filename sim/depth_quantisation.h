#pragma once
// Depth as a depth camera hands it out: whole steps of 1/scale metres, 0 where there is no
// depth (non-finite, not positive, or beyond the 16-bit range).
#include <opencv2/core/mat.hpp>

namespace viqu::sim {

// Quantises CV_32F metric depth in place to steps of 1/scale m, computing the values exactly as
// a reader converting the 16-bit image back (convertTo with factor 1/scale) does, so that a
// recorded depth PNG replays bit for bit.
void QuantiseDepth(cv::Mat* depth_m, double scale);

}  // namespace viqu::sim

#pragma once
// Depth as a depth camera, or a 16-bit depth image, holds it: whole steps of 1/steps_per_m
// metres, 0 where there is no depth (non-finite, not positive, or beyond the 16-bit range).
#include <opencv2/core/mat.hpp>

namespace viqu::sim {

// CV_32F metric depth to CV_16U steps (what the EuRoC and TUM recorders write as PNG).
// Throws RunError for another type.
cv::Mat DepthToSteps(const cv::Mat& depth_m, double steps_per_m);

// Quantises CV_32F metric depth in place to steps of 1/steps_per_m m, with the values computed
// exactly as a reader converting the 16-bit image back (convertTo with factor 1/steps_per_m)
// gets them, so that a recorded depth PNG replays bit for bit. Returns the steps (DepthToSteps
// of the input), which a recorder can write without converting again; empty for empty input.
cv::Mat QuantiseDepth(cv::Mat* depth_m, double steps_per_m);

// The steps a recorder writes for `depth_m`: `given` (QuantiseDepth's result, passed on by the
// caller) when not empty, else DepthToSteps(depth_m, steps_per_m). Throws RunError naming `who`
// when `given` is not CV_16U of the depth image's size.
cv::Mat DepthStepsToWrite(const cv::Mat& depth_m, const cv::Mat& given, double steps_per_m, const char* who);

}  // namespace viqu::sim

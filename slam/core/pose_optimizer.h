#pragma once
// Pose-only optimisation: the camera pose that best reprojects the frame's matched map points,
// with a Huber kernel and rounds of outlier classification (chi-square 95% thresholds: 5.991
// for 2-dof monocular, 7.815 for 3-dof stereo observations).
#include "slam/core/camera.h"
#include "slam/core/frame.h"

namespace viqu::slam {

struct PoseOptimizerOptions {
  int rounds = 4;           // optimise / reclassify rounds
  int iterations = 10;      // Levenberg-Marquardt iterations per round
  double huber_px = 2.447;  // kernel width for monocular residuals (stereo: scaled by sqrt(7.815/5.991))
};

// Optimises frame->T_c_w from its matched points (inliers and outliers alike are re-examined each
// round) and sets frame->outlier. Returns the number of inliers.
int OptimizePose(const StereoCamera& cam, const PoseOptimizerOptions& opt, Frame* frame);

}  // namespace viqu::slam

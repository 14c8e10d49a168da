#pragma once
// The solver of local bundle adjustment, written out: Levenberg-Marquardt on keyframe poses and
// map points with the points eliminated by the Schur complement (the reduced camera system is
// dense, 6 x free keyframes), Huber weights by iterative reweighting, analytic Jacobians for a
// left perturbation of each pose. It replaced Ceres' DENSE_SCHUR, whose generic (dynamic-size)
// eliminator, problem set-up and per-residual evaluation cost about 40 ms per keyframe.
// Deterministic: the result depends only on the inputs and their order.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "slam/core/camera.h"

namespace viqu::slam {

// One observation of point `point` in keyframe `pose`: pixel (u, v), the right image's column
// `ur` when >= 0 (stereo), and `w` = 1 / level scale (residuals are pixels of the level).
struct BaObservation {
  int pose = 0;
  int point = 0;
  double u = 0, v = 0, ur = -1, w = 1, wr = 1;
};

struct BaProblem {
  std::vector<Eigen::Isometry3d> poses;  // T_c_w; the first `free_poses` are optimised, the rest held
  int free_poses = 0;
  std::vector<Eigen::Vector3d> points;   // in the world, all optimised
  std::vector<BaObservation> observations;
};

struct BaSolverOptions {
  int iterations = 10;         // Levenberg-Marquardt steps tried at most
  double huber_mono = 2.447;   // Huber width (px) of a monocular residual
  double huber_stereo = 2.795; // and of a stereo one (3 rows): 2.447 * sqrt(7.815 / 5.991)
  // Stop when an accepted step lowers the cost by less than this fraction (Ceres' default
  // function tolerance, which the Ceres version of local BA ran with).
  double function_tolerance = 1e-6;
};

struct BaSolverSummary {
  double initial_cost = 0, final_cost = 0;  // sum of Huber costs (px^2)
  int iterations = 0, successful_steps = 0;
};

// Minimises the sum of Huber costs of the reprojection residuals over the free poses and all
// points, in place.
BaSolverSummary SolveBundleAdjustment(const StereoCamera& cam, const BaSolverOptions& opt, BaProblem* problem);

}  // namespace viqu::slam

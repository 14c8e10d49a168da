#pragma once
// Absolute trajectory error (after Umeyama alignment) and relative pose error.
#include <Eigen/Geometry>

#include "slam/eval/trajectory.h"

namespace viqu::eval {

struct ErrorStats {
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;  // (m)
  size_t count = 0;
};
ErrorStats ComputeStats(std::vector<double> errors);

// Similarity (or rigid, scale = 1) transform mapping `from` points onto `to` points in the least
// squares sense (Umeyama 1991). Needs at least 3 points; throws viqu::InputError otherwise.
struct Alignment {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double scale = 1.0;
};
Alignment UmeyamaAlign(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
                       bool with_scale);

struct AteResult {
  ErrorStats ate;                 // position errors after alignment (m)
  Alignment alignment;            // est -> gt
  size_t pairs = 0;               // associated pose pairs
};

// ATE of `est` against `gt`: associate, align est onto gt (SE(3), or Sim(3) if with_scale),
// position error per pair. Throws viqu::InputError when fewer than 3 pairs associate.
AteResult ComputeAte(const Trajectory& est, const Trajectory& gt, bool with_scale = false,
                     double max_diff_s = 0.02);

// RPE translation errors between pose pairs `delta` associated pairs apart (delta_frames > 0),
// or, when delta_m > 0, between each pose and the first later pose that is at least delta_m
// further along the ground-truth path.
ErrorStats ComputeRpe(const Trajectory& est, const Trajectory& gt, int delta_frames = 1, double delta_m = 0,
                      double max_diff_s = 0.02);

}  // namespace viqu::eval

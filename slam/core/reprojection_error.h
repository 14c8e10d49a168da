#pragma once
// The chi-square test of one observation: the squared reprojection error of a point against a
// feature (u, v, and u_right when the feature has a stereo match), in units of the feature's
// level variance, against the 95% quantile for 2 (monocular) or 3 (stereo) degrees of freedom.
// Pose optimisation, local BA, triangulation and fusion all classify observations with it.
#include <Eigen/Core>

#include "slam/core/camera.h"
#include "slam/core/frame.h"

namespace viqu::slam {

inline constexpr double kChi2Mono = 5.991;    // 95%, 2 dof
inline constexpr double kChi2Stereo = 7.815;  // 95%, 3 dof

// Error of feature `idx` for the point p_c in the camera frame; 1e9 when the point is not in
// front of the camera.
inline double ObservationChi2(const StereoCamera& cam, const FrameFeatures& f, int idx, const Eigen::Vector3d& p_c) {
  if (p_c.z() <= 1e-4) return 1e9;
  const FeaturePoint& kp = f.keypoints[idx];
  const Eigen::Vector2d uv = cam.Project(p_c);
  double e2 = (uv - Eigen::Vector2d(kp.pt.x, kp.pt.y)).squaredNorm();
  if (f.u_right[idx] >= 0) {
    const double er = uv.x() - cam.bf / p_c.z() - f.u_right[idx];
    e2 += er * er;
  }
  return e2 / f.level_sigma2[kp.octave];
}

inline bool IsInlierObservation(const StereoCamera& cam, const FrameFeatures& f, int idx, const Eigen::Vector3d& p_c) {
  return ObservationChi2(cam, f, idx, p_c) <= (f.u_right[idx] >= 0 ? kChi2Stereo : kChi2Mono);
}

}  // namespace viqu::slam

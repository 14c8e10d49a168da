#include "slam/core/pose_optimizer.h"

#include <cmath>
#include <vector>

#include "slam/core/map.h"
#include "slam/core/reprojection_cost.h"
#include "slam/core/reprojection_error.h"

namespace viqu::slam {
namespace {

struct Obs {
  int idx;
  bool stereo;
  Eigen::Vector3d p_w;
};

}  // namespace

int OptimizePose(const StereoCamera& cam, const PoseOptimizerOptions& opt, Frame* frame) {
  const FrameFeatures& f = *frame->features;
  std::vector<Obs> obs;
  for (size_t i = 0; i < frame->size(); ++i) {
    MapPoint* p = frame->points[i];
    if (!p || p->bad) continue;
    obs.push_back({static_cast<int>(i), f.u_right[i] >= 0, p->p_w});
    frame->outlier[i] = false;
  }
  if (obs.size() < 3) return 0;

  double q[6];
  PoseToParams(frame->T_c_w, q);
  const double huber_stereo = opt.huber_px * std::sqrt(kChi2Stereo / kChi2Mono);
  int inliers = 0;
  for (int round = 0; round < opt.rounds; ++round) {
    ceres::Problem::Options popt;
    popt.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(popt);
    int used = 0;
    for (const Obs& o : obs) {
      if (frame->outlier[o.idx]) continue;
      const cv::KeyPoint& kp = f.keypoints[o.idx];
      const double inv_sigma = 1.0 / f.level_scale[kp.octave];
      // The last round runs without the robust kernel (the inliers are settled by then).
      const bool robust = round < opt.rounds - 1;
      if (o.stereo) {
        auto* c = new ceres::AutoDiffCostFunction<FixedPointCost<StereoReprojectionCost>, 3, 6>(
            new FixedPointCost<StereoReprojectionCost>(
                StereoReprojectionCost(cam, kp.pt.x, kp.pt.y, f.u_right[o.idx], inv_sigma), o.p_w));
        problem.AddResidualBlock(c, robust ? new ceres::HuberLoss(huber_stereo) : nullptr, q);
      } else {
        auto* c = new ceres::AutoDiffCostFunction<FixedPointCost<ReprojectionCost>, 2, 6>(
            new FixedPointCost<ReprojectionCost>(ReprojectionCost(cam, kp.pt.x, kp.pt.y, -1, inv_sigma), o.p_w));
        problem.AddResidualBlock(c, robust ? new ceres::HuberLoss(opt.huber_px) : nullptr, q);
      }
      ++used;
    }
    if (used < 3) break;
    ceres::Solver::Options sopt;
    sopt.linear_solver_type = ceres::DENSE_QR;
    sopt.max_num_iterations = opt.iterations;
    sopt.num_threads = 1;
    sopt.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(sopt, &problem, &summary);

    const Eigen::Isometry3d T = ParamsToPose(q);
    inliers = 0;
    for (const Obs& o : obs) {
      frame->outlier[o.idx] = !IsInlierObservation(cam, f, o.idx, T * o.p_w);
      if (!frame->outlier[o.idx]) ++inliers;
    }
    if (inliers < 10) break;  // ORB-SLAM's stop: below 10 inliers more rounds only chase outliers
  }
  frame->T_c_w = ParamsToPose(q);
  return inliers;
}

}  // namespace viqu::slam

#include "slam/core/pose_optimizer.h"

#include <cmath>
#include <vector>

#include <Eigen/Cholesky>

#include "slam/core/map.h"
#include "slam/core/reprojection_error.h"
#include "slam/core/reprojection_jacobian.h"

namespace viqu::slam {
namespace {

// One matched feature: its point in the world, its measurement and its weight.
struct Obs {
  int idx;
  Eigen::Vector3d p_w;
  double u, v, ur;  // measured pixel and right-image column (< 0: monocular)
  double w;         // 1 / level scale: the residual in units of the level's pixel
  double wr;        // scale of the right-column row (StereoCamera::RightScale)
};

// Levenberg-Marquardt on the 6-dof pose, written out: analytic Jacobians of the pinhole (and
// right-column) projection for a left perturbation of the pose, Huber weights by iteratively
// reweighted least squares, the 6x6 normal equations solved directly. Ceres did the same with a
// problem (and a loss object per residual) rebuilt every round, which cost more than the solve.
class PoseSolver {
 public:
  PoseSolver(const StereoCamera& cam, const std::vector<Obs>& obs, const std::vector<uint8_t>& use)
      : cam_(cam), obs_(obs), use_(use) {}

  // Robust cost (sum of Huber rho over used observations) at `T`; fills H and g when asked.
  double Evaluate(const Eigen::Isometry3d& T, double huber_mono, double huber_stereo, bool robust,
                  Eigen::Matrix<double, 6, 6>* H, Eigen::Matrix<double, 6, 1>* g) const {
    double cost = 0;
    if (H) H->setZero();
    if (g) g->setZero();
    for (size_t k = 0; k < obs_.size(); ++k) {
      if (!use_[k]) continue;
      const Obs& o = obs_[k];
      Residual res;
      EvaluateReprojection(cam_, o.u, o.v, o.ur, o.w, T, o.p_w, H != nullptr, &res, o.wr);
      double weight = 1.0;
      const double s = res.r.squaredNorm();
      cost += robust ? HuberCost(s, o.ur >= 0 ? huber_stereo : huber_mono, &weight) : s;
      if (!H) continue;
      H->noalias() += weight * res.J_pose.transpose() * res.J_pose;
      g->noalias() += weight * res.J_pose.transpose() * res.r;
    }
    return cost;
  }

 private:
  const StereoCamera& cam_;
  const std::vector<Obs>& obs_;
  const std::vector<uint8_t>& use_;
};

// Levenberg-Marquardt iterations from `T`; returns the optimised pose.
Eigen::Isometry3d Solve(const PoseSolver& solver, Eigen::Isometry3d T, int iterations, double huber_mono,
                        double huber_stereo, bool robust) {
  double lambda = 1e-4;  // damping relative to the diagonal (Ceres' initial trust region ~ 1e4)
  Eigen::Matrix<double, 6, 6> H;
  Eigen::Matrix<double, 6, 1> g;
  double cost = solver.Evaluate(T, huber_mono, huber_stereo, robust, &H, &g);
  for (int it = 0; it < iterations; ++it) {
    bool stepped = false;
    for (int tries = 0; tries < 10 && !stepped; ++tries) {
      Eigen::Matrix<double, 6, 6> A = H;
      A.diagonal() += lambda * H.diagonal().cwiseMax(1e-9);
      const Eigen::Matrix<double, 6, 1> d = A.ldlt().solve(-g);
      if (!d.allFinite()) return T;
      const Eigen::Isometry3d candidate = PerturbLeft(T, d);
      const double new_cost = solver.Evaluate(candidate, huber_mono, huber_stereo, robust, nullptr, nullptr);
      if (new_cost < cost) {
        const bool converged = cost - new_cost < 1e-10 * cost || d.norm() < 1e-10;
        T = candidate;
        cost = solver.Evaluate(T, huber_mono, huber_stereo, robust, &H, &g);
        lambda = std::max(lambda / 10, 1e-9);
        stepped = true;
        if (converged) return T;
      } else {
        lambda *= 10;
      }
    }
    if (!stepped) break;  // no step lowers the cost: a minimum
  }
  return T;
}

}  // namespace

int OptimizePose(const StereoCamera& cam, const PoseOptimizerOptions& opt, Frame* frame) {
  const FrameFeatures& f = *frame->features;
  std::vector<Obs> obs;
  for (size_t i = 0; i < frame->size(); ++i) {
    MapPoint* p = frame->points[i];
    if (!p || p->bad) continue;
    const FeaturePoint& kp = f.keypoints[i];
    obs.push_back({static_cast<int>(i), p->p_w, kp.pt.x, kp.pt.y, cam.OptimiserColumn(f.u_right[i], f.depth[i]),
                   1.0 / f.level_scale[kp.octave], cam.RightScale(f.depth[i])});
    frame->outlier[i] = false;
  }
  if (obs.size() < 3) return 0;

  const double huber_stereo = opt.huber_px * std::sqrt(kChi2Stereo / kChi2Mono);
  std::vector<uint8_t> use(obs.size(), 1);
  const PoseSolver solver(cam, obs, use);
  Eigen::Isometry3d T = frame->T_c_w;
  int inliers = 0;
  for (int round = 0; round < opt.rounds; ++round) {
    int used = 0;
    for (size_t k = 0; k < obs.size(); ++k) {
      use[k] = !frame->outlier[obs[k].idx];
      used += use[k];
    }
    if (used < 3) break;
    // The last round runs without the robust kernel (the inliers are settled by then).
    const bool robust = round < opt.rounds - 1;
    T = Solve(solver, T, opt.iterations, opt.huber_px, huber_stereo, robust);
    inliers = 0;
    for (const Obs& o : obs) {
      frame->outlier[o.idx] = !IsInlierObservation(cam, f, o.idx, T * o.p_w);
      if (!frame->outlier[o.idx]) ++inliers;
    }
    if (inliers < 10) break;  // ORB-SLAM's stop: below 10 inliers more rounds only chase outliers
  }
  frame->T_c_w = T;
  return inliers;
}

}  // namespace viqu::slam

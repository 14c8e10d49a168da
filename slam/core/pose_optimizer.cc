#include "slam/core/pose_optimizer.h"

#include <cmath>
#include <vector>

#include <Eigen/Cholesky>

#include "slam/core/map.h"
#include "slam/core/reprojection_error.h"

namespace viqu::slam {
namespace {

// One matched feature: its point in the world, its measurement and its weight.
struct Obs {
  int idx;
  bool stereo;
  Eigen::Vector3d p_w;
  double u, v, ur;  // measured pixel (and right-image column when stereo)
  double w;         // 1 / level scale: the residual in units of the level's pixel
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
      const Eigen::Vector3d p = T * o.p_w;
      const double z = p.z() < 1e-4 ? 1e-4 : p.z();  // as the Ceres cost clamped it
      const double inv_z = 1.0 / z;
      const double u = cam_.fx * p.x() * inv_z + cam_.cx;
      const double v = cam_.fy * p.y() * inv_z + cam_.cy;
      Eigen::Vector3d r;
      r << (u - o.u) * o.w, (v - o.v) * o.w, o.stereo ? (u - cam_.bf * inv_z - o.ur) * o.w : 0.0;
      const double s = r.squaredNorm();
      const double a = o.stereo ? huber_stereo : huber_mono;
      double weight = 1.0;
      if (robust && s > a * a) {
        const double norm = std::sqrt(s);
        cost += 2 * a * norm - a * a;
        weight = a / norm;
      } else {
        cost += s;
      }
      if (!H) continue;
      // d(u, v, ur)/dp at p (z clamped as above), then dp/d(omega, nu) = [-[p]x, I].
      Eigen::Matrix<double, 3, 3> Jp = Eigen::Matrix3d::Zero();
      const double inv_z2 = inv_z * inv_z;
      Jp(0, 0) = cam_.fx * inv_z;
      Jp(0, 2) = -cam_.fx * p.x() * inv_z2;
      Jp(1, 1) = cam_.fy * inv_z;
      Jp(1, 2) = -cam_.fy * p.y() * inv_z2;
      if (o.stereo) {
        Jp(2, 0) = cam_.fx * inv_z;
        Jp(2, 2) = (cam_.bf - cam_.fx * p.x()) * inv_z2;
      }
      if (p.z() < 1e-4) Jp.col(2).setZero();  // the clamp makes the residual flat in z there
      Eigen::Matrix3d skew;
      skew << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() = -Jp * skew;
      J.rightCols<3>() = Jp;
      J *= o.w;
      if (!o.stereo) J.row(2).setZero();  // a monocular residual has two rows (r(2) is 0 too)
      H->noalias() += weight * J.transpose() * J;
      g->noalias() += weight * J.transpose() * r;
    }
    return cost;
  }

 private:
  const StereoCamera& cam_;
  const std::vector<Obs>& obs_;
  const std::vector<uint8_t>& use_;
};

// T moved by the left perturbation (omega, nu): R(omega) * T, translated by nu.
Eigen::Isometry3d Perturb(const Eigen::Isometry3d& T, const Eigen::Matrix<double, 6, 1>& d) {
  const Eigen::Vector3d omega = d.head<3>();
  const double angle = omega.norm();
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  if (angle > 1e-15) D.linear() = Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
  D.translation() = d.tail<3>();
  Eigen::Isometry3d out = D * T;
  // Keep the rotation orthonormal over many small steps.
  out.linear() = Eigen::Quaterniond(out.rotation()).normalized().toRotationMatrix();
  return out;
}

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
      const Eigen::Isometry3d candidate = Perturb(T, d);
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
    const cv::KeyPoint& kp = f.keypoints[i];
    obs.push_back({static_cast<int>(i), f.u_right[i] >= 0, p->p_w, kp.pt.x, kp.pt.y, f.u_right[i],
                   1.0 / f.level_scale[kp.octave]});
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

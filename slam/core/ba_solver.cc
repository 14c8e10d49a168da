#include "slam/core/ba_solver.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "slam/core/reprojection_jacobian.h"

namespace viqu::slam {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat63 = Eigen::Matrix<double, 6, 3>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

class Solver {
 public:
  Solver(const StereoCamera& cam, const BaSolverOptions& opt, const BaProblem& problem)
      : cam_(cam), opt_(opt), pb_(problem) {
    const size_t n_points = pb_.points.size();
    // Observations grouped by point (stable: the given order within a point).
    by_point_begin_.assign(n_points + 1, 0);
    for (const BaObservation& o : pb_.observations) ++by_point_begin_[o.point + 1];
    for (size_t j = 0; j < n_points; ++j) by_point_begin_[j + 1] += by_point_begin_[j];
    order_.resize(pb_.observations.size());
    std::vector<int> fill(by_point_begin_.begin(), by_point_begin_.end() - 1);
    for (size_t i = 0; i < pb_.observations.size(); ++i) order_[fill[pb_.observations[i].point]++] = static_cast<int>(i);
    W_.resize(pb_.observations.size());
    Hxx_.resize(n_points);
    gx_.resize(n_points);
    Vinv_.resize(n_points);
  }

  double Cost(const std::vector<Eigen::Isometry3d>& poses, const std::vector<Eigen::Vector3d>& points) const {
    double cost = 0;
    Residual res;
    for (const BaObservation& o : pb_.observations) {
      EvaluateReprojection(cam_, o.u, o.v, o.ur, o.w, poses[o.pose], points[o.point], false, &res, o.wr);
      cost += HuberCost(res.r.squaredNorm(), o.ur >= 0 ? opt_.huber_stereo : opt_.huber_mono, nullptr);
    }
    return cost;
  }

  // Builds the Gauss-Newton system (IRLS weights) at the current estimate.
  void Linearise(const std::vector<Eigen::Isometry3d>& poses, const std::vector<Eigen::Vector3d>& points) {
    const int F = pb_.free_poses;
    Hpp_.assign(F, Mat6::Zero());
    gp_.assign(F, Vec6::Zero());
    Residual res;
    for (size_t j = 0; j < points.size(); ++j) {
      Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      for (int k = by_point_begin_[j]; k < by_point_begin_[j + 1]; ++k) {
        const BaObservation& o = pb_.observations[order_[k]];
        EvaluateReprojection(cam_, o.u, o.v, o.ur, o.w, poses[o.pose], points[j], true, &res, o.wr);
        double wt;
        HuberCost(res.r.squaredNorm(), o.ur >= 0 ? opt_.huber_stereo : opt_.huber_mono, &wt);
        const Eigen::Matrix3d JxT_w = wt * res.J_point.transpose();
        H.noalias() += JxT_w * res.J_point;
        g.noalias() += JxT_w * res.r;
        if (o.pose < F) {
          const Eigen::Matrix<double, 6, 3> JpT_w = wt * res.J_pose.transpose();
          Hpp_[o.pose].noalias() += JpT_w * res.J_pose;
          gp_[o.pose].noalias() += JpT_w * res.r;
          W_[k].noalias() = JpT_w * res.J_point;
        }
      }
      Hxx_[j] = H;
      gx_[j] = g;
    }
  }

  // Solves the damped system (H + lambda diag(H)) delta = -g by eliminating the points.
  void Step(double lambda, std::vector<Vec6>* dp, std::vector<Eigen::Vector3d>* dx) {
    const int F = pb_.free_poses;
    const size_t n_points = Hxx_.size();
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(6 * F, 6 * F);
    Eigen::VectorXd rhs(6 * F);
    for (int k = 0; k < F; ++k) {
      Mat6 A = Hpp_[k];
      A.diagonal() += lambda * Hpp_[k].diagonal().cwiseMax(1e-9);
      S.block<6, 6>(6 * k, 6 * k) = A;
      rhs.segment<6>(6 * k) = -gp_[k];
    }
    std::vector<Mat63> Y;  // W V^-1 of each free observation of a point
    std::vector<int> Y_pose;
    for (size_t j = 0; j < n_points; ++j) {
      Eigen::Matrix3d V = Hxx_[j];
      V.diagonal() += lambda * Hxx_[j].diagonal().cwiseMax(1e-9);
      Vinv_[j] = V.inverse();
      Y.clear();
      Y_pose.clear();
      for (int k = by_point_begin_[j]; k < by_point_begin_[j + 1]; ++k) {
        const int pose = pb_.observations[order_[k]].pose;
        if (pose >= F) continue;
        Y.push_back(W_[k] * Vinv_[j]);
        Y_pose.push_back(pose);
        rhs.segment<6>(6 * pose).noalias() += Y.back() * gx_[j];
      }
      int a = 0;
      for (int k = by_point_begin_[j]; k < by_point_begin_[j + 1]; ++k) {
        if (pb_.observations[order_[k]].pose >= F) continue;
        // S(pa, pb) -= Y_a W_b^T for b <= a (the lower triangle; LDLT reads only that).
        int b = 0;
        for (int l = by_point_begin_[j]; l <= k; ++l) {
          if (pb_.observations[order_[l]].pose >= F) continue;
          const int pa = Y_pose[a], pbose = Y_pose[b];
          if (pa >= pbose) {
            S.block<6, 6>(6 * pa, 6 * pbose).noalias() -= Y[a] * W_[l].transpose();
          } else {
            S.block<6, 6>(6 * pbose, 6 * pa).noalias() -= W_[l] * Y[a].transpose();
          }
          ++b;
        }
        ++a;
      }
    }
    const Eigen::VectorXd x = S.selfadjointView<Eigen::Lower>().ldlt().solve(rhs);
    dp->resize(F);
    for (int k = 0; k < F; ++k) (*dp)[k] = x.segment<6>(6 * k);
    dx->resize(n_points);
    for (size_t j = 0; j < n_points; ++j) {
      Eigen::Vector3d b = -gx_[j];
      for (int k = by_point_begin_[j]; k < by_point_begin_[j + 1]; ++k) {
        const int pose = pb_.observations[order_[k]].pose;
        if (pose < F) b.noalias() -= W_[k].transpose() * (*dp)[pose];
      }
      (*dx)[j] = Vinv_[j] * b;
    }
  }

 private:
  const StereoCamera& cam_;
  const BaSolverOptions& opt_;
  const BaProblem& pb_;
  std::vector<int> by_point_begin_, order_;  // observations of point j: order_[begin[j] .. begin[j+1])
  std::vector<Mat6> Hpp_;
  std::vector<Vec6> gp_;
  std::vector<Mat63> W_;  // J_pose^T w J_point per observation (in order_), free poses only
  std::vector<Eigen::Matrix3d> Hxx_, Vinv_;
  std::vector<Eigen::Vector3d> gx_;
};

}  // namespace

BaSolverSummary SolveBundleAdjustment(const StereoCamera& cam, const BaSolverOptions& opt, BaProblem* problem) {
  BaSolverSummary sum;
  Solver solver(cam, opt, *problem);
  double cost = solver.Cost(problem->poses, problem->points);
  sum.initial_cost = sum.final_cost = cost;
  if (problem->observations.empty()) return sum;
  // Damping relative to the diagonal, as Ceres' initial trust region (1e4) gives.
  double lambda = 1e-4;
  solver.Linearise(problem->poses, problem->points);
  std::vector<Vec6> dp;
  std::vector<Eigen::Vector3d> dx;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<Eigen::Vector3d> points;
  for (int it = 0; it < opt.iterations; ++it) {
    ++sum.iterations;
    solver.Step(lambda, &dp, &dx);
    poses = problem->poses;
    points = problem->points;
    bool finite = true;
    for (int k = 0; k < problem->free_poses; ++k) {
      finite = finite && dp[k].allFinite();
      poses[k] = PerturbLeft(problem->poses[k], dp[k]);
    }
    for (size_t j = 0; j < points.size(); ++j) {
      finite = finite && dx[j].allFinite();
      points[j] += dx[j];
    }
    const double new_cost = finite ? solver.Cost(poses, points) : cost;
    if (finite && new_cost < cost) {
      const bool converged = cost - new_cost < opt.function_tolerance * cost;
      problem->poses.swap(poses);
      problem->points.swap(points);
      cost = new_cost;
      ++sum.successful_steps;
      lambda = std::max(lambda / 3, 1e-12);  // Ceres shrinks its damping by up to 3 on a good step
      if (converged) break;
      solver.Linearise(problem->poses, problem->points);
    } else {
      lambda *= 10;
    }
  }
  sum.final_cost = cost;
  return sum;
}

}  // namespace viqu::slam

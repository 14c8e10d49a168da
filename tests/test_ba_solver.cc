// Local BA's written-out solver (slam/core/ba_solver.h) on synthetic keyframes and points:
//  - it reaches the minimum Ceres reaches on the same problem (the residuals of
//    ceres_reprojection_cost.h with automatic differentiation, the same Huber widths,
//    DENSE_SCHUR: what local BA ran before) - the same cost and the same poses and points;
//  - it recovers the true poses from perturbed ones, with gross outliers that the Huber kernel
//    keeps from pulling, and held keyframes stay where they are;
//  - monocular observations (no right column) count as two rows;
//  - an observation's right-column weight (BaObservation::wr) sets how far a biased right
//    column pulls.
#include <cmath>
#include <random>
#include <vector>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "slam/core/ba_solver.h"
#include "ceres_reprojection_cost.h"
#include "random_vector.h"
#include "synthetic_camera.h"

namespace viqu::slam {
namespace {

struct Scene {
  BaProblem truth;    // true poses and points
  BaProblem problem;  // perturbed start, noisy observations
  std::vector<int> outliers;
};

// `keyframes` cameras 0.15 m apart along x, turning slightly, looking along +z; `n` points
// 1.5-5 m ahead; each point seen by the keyframes in whose image it falls; pixel noise
// `noise_px`; every 25th observation moved by 30 px (outliers when `outliers`); stereo for
// every other point. The first `held` keyframes are held; the others start 2 cm / 0.5 deg off
// and the points 3 cm off.
Scene MakeScene(int keyframes, int held, int n, double noise_px, bool outliers, unsigned seed) {
  const StereoCamera cam = testing::SyntheticStereoCamera();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, noise_px);
  std::normal_distribution<double> P(0, 1);
  Scene s;
  for (int k = 0; k < keyframes; ++k) {
    const Eigen::Isometry3d T_w_c =
        Eigen::Translation3d(0.15 * k, 0.01 * std::sin(k), 0) * Eigen::AngleAxisd(0.03 * k, Eigen::Vector3d::UnitY());
    s.truth.poses.push_back(T_w_c.inverse());
  }
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d r = testing::RandomVector(U, rng);
    s.truth.points.emplace_back((r.x() - 0.5) * 4 + 0.4, (r.y() - 0.5) * 2.5, 1.5 + 3.5 * r.z());
  }
  s.truth.free_poses = s.problem.free_poses = keyframes - held;
  // Held keyframes last, as local BA orders them.
  std::vector<int> order;
  for (int k = held; k < keyframes; ++k) order.push_back(k);
  for (int k = 0; k < held; ++k) order.push_back(k);
  std::vector<Eigen::Isometry3d> poses;
  for (int k : order) poses.push_back(s.truth.poses[k]);
  s.truth.poses = poses;
  int count = 0;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < keyframes; ++k) {
      const Eigen::Vector3d p_c = s.truth.poses[k] * s.truth.points[i];
      if (p_c.z() < 0.5) continue;
      const Eigen::Vector2d uv = cam.Project(p_c);
      if (uv.x() < 0 || uv.y() < 0 || uv.x() > cam.width || uv.y() > cam.height) continue;
      BaObservation o;
      o.pose = k;
      o.point = i;
      double du = N(rng), dv = N(rng), dr = N(rng);
      if (outliers && ++count % 25 == 0) {
        du += 30;
        s.outliers.push_back(static_cast<int>(s.problem.observations.size()));
      }
      o.u = uv.x() + du;
      o.v = uv.y() + dv;
      o.ur = i % 2 == 0 ? cam.ProjectRight(p_c) + du + dr : -1;
      o.w = 1.0;
      s.problem.observations.push_back(o);
    }
  }
  s.problem.poses = s.truth.poses;
  for (int k = 0; k < s.problem.free_poses; ++k) {
    const Eigen::Vector3d dt = 0.02 * testing::RandomVector(P, rng).normalized();
    const Eigen::Vector3d axis = testing::RandomVector(P, rng).normalized();
    s.problem.poses[k] = Eigen::Translation3d(dt) * Eigen::AngleAxisd(0.5 * M_PI / 180, axis) * s.problem.poses[k];
  }
  for (const Eigen::Vector3d& p : s.truth.points) s.problem.points.push_back(p + 0.03 * testing::RandomVector(P, rng).normalized());
  return s;
}

// The same problem through Ceres (what local BA ran before): returns Ceres' cost (half the sum
// of Huber costs) and writes its poses and points into `out`.
double SolveWithCeres(const StereoCamera& cam, const BaSolverOptions& opt, BaProblem* out) {
  std::vector<std::array<double, 6>> poses(out->poses.size());
  for (size_t k = 0; k < poses.size(); ++k) PoseToParams(out->poses[k], poses[k].data());
  std::vector<std::array<double, 3>> points(out->points.size());
  for (size_t j = 0; j < points.size(); ++j) points[j] = {out->points[j].x(), out->points[j].y(), out->points[j].z()};
  ceres::Problem::Options popt;
  popt.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(popt);
  ceres::HuberLoss mono(opt.huber_mono), stereo(opt.huber_stereo);
  for (const BaObservation& o : out->observations) {
    double* pose = poses[o.pose].data();
    double* pt = points[o.point].data();
    if (o.ur >= 0) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<StereoReprojectionCost, 3, 6, 3>(
                                   new StereoReprojectionCost(cam, o.u, o.v, o.ur, o.w)),
                               &stereo, pose, pt);
    } else {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 6, 3>(
                                   new ReprojectionCost(cam, o.u, o.v, -1, o.w)),
                               &mono, pose, pt);
    }
  }
  for (size_t k = out->free_poses; k < poses.size(); ++k) {
    if (problem.HasParameterBlock(poses[k].data())) problem.SetParameterBlockConstant(poses[k].data());
  }
  ceres::Solver::Options sopt;
  sopt.linear_solver_type = ceres::DENSE_SCHUR;
  sopt.max_num_iterations = 200;
  sopt.function_tolerance = 1e-12;
  sopt.gradient_tolerance = 1e-14;
  sopt.parameter_tolerance = 1e-12;
  sopt.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(sopt, &problem, &summary);
  for (size_t k = 0; k < poses.size(); ++k) out->poses[k] = ParamsToPose(poses[k].data());
  for (size_t j = 0; j < points.size(); ++j) out->points[j] = Eigen::Vector3d(points[j][0], points[j][1], points[j][2]);
  return summary.final_cost;
}

double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}

TEST(BaSolver, ReachesTheMinimumCeresReaches) {
  const StereoCamera cam = testing::SyntheticStereoCamera();
  for (bool outliers : {false, true}) {
    const Scene s = MakeScene(8, 2, 400, 0.7, outliers, 5);
    BaSolverOptions opt;
    opt.iterations = 200;
    opt.function_tolerance = 1e-12;
    BaProblem ours = s.problem, theirs = s.problem;
    const BaSolverSummary sum = SolveBundleAdjustment(cam, opt, &ours);
    const double ceres_cost = SolveWithCeres(cam, opt, &theirs);
    std::printf("outliers %d: %zu observations; cost %.6f -> %.6f in %d steps (%d successful); Ceres %.6f\n", outliers,
                s.problem.observations.size(), 0.5 * sum.initial_cost, 0.5 * sum.final_cost, sum.iterations, sum.successful_steps,
                ceres_cost);
    EXPECT_NEAR(0.5 * sum.final_cost, ceres_cost, 1e-6 * ceres_cost);
    // The minimum is below the cost of the true state under the same noisy observations.
    BaProblem at_truth = s.truth;
    at_truth.observations = s.problem.observations;
    BaSolverOptions none = opt;
    none.iterations = 0;
    const double truth_cost = SolveBundleAdjustment(cam, none, &at_truth).initial_cost;
    EXPECT_LT(sum.final_cost, truth_cost);
    EXPECT_GT(sum.initial_cost, truth_cost);
    for (size_t k = 0; k < ours.poses.size(); ++k) {
      EXPECT_LT(PoseError(ours.poses[k], theirs.poses[k]), 1e-6) << "pose " << k;
      EXPECT_LT(Eigen::AngleAxisd(ours.poses[k].linear() * theirs.poses[k].linear().transpose()).angle(), 1e-6);
    }
    for (size_t j = 0; j < ours.points.size(); ++j) EXPECT_LT((ours.points[j] - theirs.points[j]).norm(), 1e-5) << j;
  }
}

TEST(BaSolver, RecoversThePosesWithOutliersAndHoldsTheHeldOnes) {
  const StereoCamera cam = testing::SyntheticStereoCamera();
  const Scene s = MakeScene(10, 3, 600, 0.5, true, 9);
  ASSERT_GT(s.outliers.size(), 20u);
  BaProblem p = s.problem;
  BaSolverOptions opt;  // local BA's defaults: 10 steps at most
  const BaSolverSummary sum = SolveBundleAdjustment(cam, opt, &p);
  EXPECT_GT(sum.successful_steps, 0);
  double worst_start = 0, worst = 0;
  for (int k = 0; k < p.free_poses; ++k) {
    worst_start = std::max(worst_start, PoseError(s.problem.poses[k], s.truth.poses[k]));
    worst = std::max(worst, PoseError(p.poses[k], s.truth.poses[k]));
  }
  // The same run to convergence: how far the minimum itself lies from the truth.
  BaProblem converged = s.problem;
  BaSolverOptions full = opt;
  full.iterations = 200;
  full.function_tolerance = 1e-12;
  SolveBundleAdjustment(cam, full, &converged);
  double worst_at_minimum = 0;
  for (int k = 0; k < p.free_poses; ++k) {
    worst_at_minimum = std::max(worst_at_minimum, PoseError(converged.poses[k], s.truth.poses[k]));
  }
  std::printf("worst free keyframe %.4f m at the start, %.5f m after %d steps, %.5f m at the minimum\n", worst_start,
              worst, sum.iterations, worst_at_minimum);
  EXPECT_GT(worst_start, 0.015);
  EXPECT_LT(worst, 2 * worst_at_minimum + 1e-4);
  for (size_t k = p.free_poses; k < p.poses.size(); ++k) {
    EXPECT_TRUE(p.poses[k].matrix() == s.problem.poses[k].matrix()) << "held keyframe " << k << " moved";
  }
}

TEST(BaSolver, MonocularOnlyObservationsConverge) {
  const StereoCamera cam = testing::SyntheticStereoCamera();
  Scene s = MakeScene(8, 2, 400, 0.5, false, 3);
  for (BaObservation& o : s.problem.observations) o.ur = -1;
  BaProblem ours = s.problem, theirs = s.problem;
  BaSolverOptions opt;
  opt.iterations = 50;
  opt.function_tolerance = 1e-12;
  const BaSolverSummary sum = SolveBundleAdjustment(cam, opt, &ours);
  const double ceres_cost = SolveWithCeres(cam, opt, &theirs);
  EXPECT_NEAR(0.5 * sum.final_cost, ceres_cost, 1e-6 * ceres_cost);
}

// stereo.near_right_weight_ba: local BA scales the right-column row of near observations by
// wr = sqrt(weight) (StereoCamera::RightScale). Noise-free observations whose right column is
// 1.5 px too far left (the disparity too large) wherever the point is nearer than 2.5 m to the
// keyframe: at wr 1 they pull the free keyframes; at wr 0 the row is void and the solution is
// the truth; a tenth of the weight pulls part of the way.
TEST(BaSolver, RightColumnWeightSetsHowFarABiasedColumnPulls) {
  const StereoCamera cam = testing::SyntheticStereoCamera();
  auto solve = [&](double wr) {
    Scene s = MakeScene(8, 2, 400, 0.0, false, 4);
    int biased = 0;
    for (BaObservation& o : s.problem.observations) {
      if (o.ur < 0 || (s.truth.poses[o.pose] * s.truth.points[o.point]).z() >= 2.5) continue;
      o.ur -= 1.5;
      o.wr = wr;
      ++biased;
    }
    EXPECT_GT(biased, 100);
    BaSolverOptions opt;
    opt.iterations = 100;
    opt.function_tolerance = 1e-14;
    SolveBundleAdjustment(cam, opt, &s.problem);
    double worst = 0;
    for (int k = 0; k < s.problem.free_poses; ++k) worst = std::max(worst, PoseError(s.problem.poses[k], s.truth.poses[k]));
    return 1000 * worst;
  };
  const double full_mm = solve(1.0), void_mm = solve(0.0), tenth_mm = solve(std::sqrt(0.1));
  std::printf("worst free keyframe: weight 1 %.3f mm, 0.1 %.3f mm, 0 %.6f mm\n", full_mm, tenth_mm, void_mm);
  EXPECT_LT(void_mm, 1e-3);
  EXPECT_GT(full_mm, 12);               // measured 23.7 mm
  EXPECT_LT(tenth_mm, 0.45 * full_mm);  // measured 0.23x (5.4 mm)
  EXPECT_GT(tenth_mm, 2.5);
}

}  // namespace
}  // namespace viqu::slam

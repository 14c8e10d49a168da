// Local BA's residual with Jacobians written out (slam/core/local_ba.h) against the automatic
// differentiation of the same residual (slam/core/reprojection_cost.h) that it replaced, and
// against central differences. Near a zero rotation Ceres' AngleAxisRotatePoint switches to a
// first-order formula whose Jet derivatives are off by about 2e-7 (relative) from the central
// difference, which the written-out Jacobian matches to 1e-9; there only central differences
// are the reference.
#include <memory>
#include <random>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "slam/core/local_ba.h"
#include "slam/core/reprojection_cost.h"

namespace viqu::slam {
namespace {

template <int Rows, class Cost>
void Compare(const StereoCamera& cam, bool stereo, double angle_scale, bool against_autodiff, std::mt19937* rng) {
  std::uniform_real_distribution<double> U(-1, 1);
  const double ur = stereo ? 250.0 : -1.0;
  std::unique_ptr<ceres::CostFunction> analytic(MakeBaReprojectionCost(cam, 300.0, 200.0, ur, 0.8));
  ceres::AutoDiffCostFunction<Cost, Rows, 6, 3> autodiff(new Cost(cam, 300.0, 200.0, ur, 0.8));
  ceres::NumericDiffCostFunction<Cost, ceres::CENTRAL, Rows, 6, 3> numeric(new Cost(cam, 300.0, 200.0, ur, 0.8));
  ceres::CostFunction& reference = against_autodiff ? static_cast<ceres::CostFunction&>(autodiff) : numeric;
  const double tol = against_autodiff ? 1e-7 : 1e-5;  // central differences are good to about 1e-6
  for (int trial = 0; trial < 200; ++trial) {
    double pose[6] = {angle_scale * U(*rng), angle_scale * U(*rng), angle_scale * U(*rng), 0.3 * U(*rng),
                      0.3 * U(*rng), 0.3 * U(*rng)};
    double point[3] = {U(*rng), U(*rng), 2.5 + U(*rng)};
    const double* params[2] = {pose, point};
    double r_a[Rows], r_b[Rows], jp_a[Rows * 6], jp_b[Rows * 6], jx_a[Rows * 3], jx_b[Rows * 3];
    double* j_a[2] = {jp_a, jx_a};
    double* j_b[2] = {jp_b, jx_b};
    ASSERT_TRUE(analytic->Evaluate(params, r_a, j_a));
    ASSERT_TRUE(reference.Evaluate(params, r_b, j_b));
    for (int i = 0; i < Rows; ++i) EXPECT_NEAR(r_a[i], r_b[i], 1e-9 * (1 + std::abs(r_b[i])));
    for (int i = 0; i < Rows * 6; ++i) EXPECT_NEAR(jp_a[i], jp_b[i], tol * (1 + std::abs(jp_b[i]))) << "pose " << i << " angle scale " << angle_scale;
    for (int i = 0; i < Rows * 3; ++i) EXPECT_NEAR(jx_a[i], jx_b[i], tol * (1 + std::abs(jx_b[i]))) << "point " << i;
  }
}

TEST(BaCost, AnalyticJacobiansEqualAutomaticDifferentiation) {
  StereoCamera cam;
  cam.width = 640;
  cam.height = 480;
  cam.fx = cam.fy = 415.7;
  cam.cx = 319.5;
  cam.cy = 239.5;
  cam.bf = 415.7 * 0.04;
  std::mt19937 rng(3);
  for (double angle_scale : {1.5, 0.1}) {  // large and small rotations
    Compare<3, StereoReprojectionCost>(cam, true, angle_scale, true, &rng);
    Compare<2, ReprojectionCost>(cam, false, angle_scale, true, &rng);
  }
  for (double angle_scale : {0.1, 1e-9}) {  // and near zero, against central differences (points well in front)
    Compare<3, StereoReprojectionCost>(cam, true, angle_scale, false, &rng);
    Compare<2, ReprojectionCost>(cam, false, angle_scale, false, &rng);
  }
}

}  // namespace
}  // namespace viqu::slam

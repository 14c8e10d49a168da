// ATE/RPE against independent computations: Eigen's own umeyama() for the alignment, a
// hand-worked trajectory with a known rigid offset and noise, and associate.py's matching rule.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/errors.h"
#include "slam/eval/trajectory_error.h"
#include "random_vector.h"

namespace viqu::eval {
namespace {

StampedPose Pose(double t_s, const Eigen::Vector3d& p, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  StampedPose s;
  s.t_ns = std::llround(t_s * 1e9);
  s.p_w_x = p;
  s.q_w_x = q;
  return s;
}

Eigen::Isometry3d KnownOffset() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, -0.5, 1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.5, -2.0, 0.3);
  return T;
}

TEST(TrajectoryEval, RigidOffsetWithoutNoiseGivesZeroError) {
  Trajectory gt, est;
  const Eigen::Isometry3d T = KnownOffset();
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d p(0.1 * i, std::sin(0.2 * i), 0.05 * std::cos(0.3 * i));
    gt.push_back(Pose(0.05 * i, p));
    est.push_back(Pose(0.05 * i, T * p, Eigen::Quaterniond(T.linear())));
  }
  const AteResult r = ComputeAte(est, gt);
  EXPECT_EQ(r.pairs, 50u);
  EXPECT_LT(r.ate.rmse, 1e-9);
  EXPECT_LT((r.alignment.R - T.linear().transpose()).norm(), 1e-9);
  EXPECT_LT(ComputeRpe(est, gt).rmse, 1e-9);
}

TEST(TrajectoryEval, HandWorkedNoiseSurvivesAlignmentExactly) {
  // Every ground-truth position appears twice in a row, with noise +e and then -e along z in the
  // estimate. The noise then has zero mean and zero covariance with the positions, so the
  // cross-covariance that Umeyama aligns by is the noise-free one: the best alignment is exactly
  // the inverse offset and every pair's error is exactly e.
  const double e = 0.01;
  Trajectory gt, est;
  const Eigen::Isometry3d T = KnownOffset();
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d p(0.1 * k, 0.3 * std::sin(0.4 * k), 0.02 * k);
    for (int s = 0; s < 2; ++s) {
      const double t = 0.1 * k + 0.05 * s;
      gt.push_back(Pose(t, p));
      est.push_back(Pose(t, T * (p + Eigen::Vector3d(0, 0, s ? -e : e))));
    }
  }
  const AteResult r = ComputeAte(est, gt);
  EXPECT_EQ(r.pairs, 40u);
  EXPECT_NEAR(r.ate.rmse, e, 1e-6);
  EXPECT_NEAR(r.ate.mean, e, 1e-6);
  EXPECT_NEAR(r.ate.median, e, 1e-6);
  EXPECT_NEAR(r.ate.std, 0, 1e-6);
  EXPECT_NEAR(r.ate.min, e, 1e-6);
  EXPECT_NEAR(r.ate.max, e, 1e-6);
  EXPECT_LT((r.alignment.R - T.linear().transpose()).norm(), 1e-9);
}

TEST(TrajectoryEval, MatchesEigenUmeyamaOnRandomNoise) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n(0, 0.02);
  Trajectory gt, est;
  const Eigen::Isometry3d T = KnownOffset();
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p(0.02 * i, std::sin(0.05 * i), 0.2 * std::cos(0.03 * i));
    gt.push_back(Pose(0.05 * i, p));
    est.push_back(Pose(0.05 * i, T * p + testing::RandomVector(n, rng)));
  }
  for (bool scale : {false, true}) {
    const AteResult r = ComputeAte(est, gt, scale);
    Eigen::Matrix3Xd from(3, 200), to(3, 200);
    for (int i = 0; i < 200; ++i) {
      from.col(i) = est[i].p_w_x;
      to.col(i) = gt[i].p_w_x;
    }
    const Eigen::Matrix4d M = Eigen::umeyama(from, to, scale);
    double sum_sq = 0, sum = 0, mx = 0;
    for (int i = 0; i < 200; ++i) {
      const double err = (to.col(i) - (M.topLeftCorner<3, 3>() * from.col(i) + M.topRightCorner<3, 1>())).norm();
      sum_sq += err * err;
      sum += err;
      mx = std::max(mx, err);
    }
    EXPECT_NEAR(r.ate.rmse, std::sqrt(sum_sq / 200), 1e-6) << "scale " << scale;
    EXPECT_NEAR(r.ate.mean, sum / 200, 1e-6);
    EXPECT_NEAR(r.ate.max, mx, 1e-6);
  }
}

TEST(TrajectoryEval, AssociatesGreedilyBySmallestDifferenceEachStampOnce) {
  // est stamps 1.000 and 1.012; gt stamps 1.010 and 1.030. Candidates within 0.02 s:
  // (1.012,1.010) d=0.002, (1.000,1.010) d=0.010, (1.012,1.030) d=0.018. Greedy: first pair
  // (1.012,1.010); then (1.000,1.010) is blocked (gt used) and (1.012,1.030) is blocked (est used).
  Trajectory est = {Pose(1.000, {0, 0, 0}), Pose(1.012, {0, 0, 0})};
  Trajectory gt = {Pose(1.010, {0, 0, 0}), Pose(1.030, {0, 0, 0})};
  const auto pairs = Associate(est, gt, 0.02);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], (std::pair<size_t, size_t>(1, 0)));
  EXPECT_TRUE(Associate(est, {Pose(1.5, {0, 0, 0})}, 0.02).empty());
}

TEST(TrajectoryEval, RpeOverMetresUsesGroundTruthPathLength) {
  // Straight line along x at 0.1 m per pose; the estimate drifts 1% in scale. With delta 1 m the
  // pairs are 10 poses apart and each relative motion is off by 0.01 m.
  Trajectory gt, est;
  for (int i = 0; i <= 30; ++i) {
    gt.push_back(Pose(0.1 * i, {0.1 * i, 0, 0}));
    est.push_back(Pose(0.1 * i, {0.101 * i, 0, 0}));
  }
  const ErrorStats r = ComputeRpe(est, gt, 1, 1.0);
  EXPECT_EQ(r.count, 21u);
  EXPECT_NEAR(r.rmse, 0.01, 1e-9);
}

TEST(TrajectoryEval, BadFilesAreInputErrorsWithFileAndLine) {
  const auto dir = std::filesystem::temp_directory_path() / "viqu_eval_test";
  std::filesystem::create_directories(dir);
  const std::string bad = (dir / "bad.txt").string();
  std::ofstream(bad) << "# header\n0.0 0 0 0 0 0 0 1\n0.1 0 0 zero 0 0 0 1\n";
  try {
    ReadTumTrajectory(bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":3:"), std::string::npos) << e.what();
  }
  const std::string back = (dir / "back.txt").string();
  std::ofstream(back) << "1.0 0 0 0 0 0 0 1\n0.5 0 0 0 0 0 0 1\n";
  EXPECT_THROW(ReadTumTrajectory(back), InputError);
  EXPECT_THROW(ReadTumTrajectory((dir / "missing.txt").string()), InputError);
  // A NaN or an infinity is named as such, not as a malformed line; too few or too many fields are.
  auto error_of = [&](const std::string& text) {
    std::ofstream(bad) << text;
    try {
      ReadTumTrajectory(bad);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("<no InputError>");
  };
  EXPECT_EQ(error_of("0.0 0 0 0 0 0 0 1\n0.1 nan 0 0 0 0 0 1\n"), bad + ":2: value is not a finite number");
  EXPECT_EQ(error_of("0.0 0 0 inf 0 0 0 1\n"), bad + ":1: value is not a finite number");
  EXPECT_EQ(error_of("0.0 0 0 0 0 0 1\n"), bad + ":1: expected 8 numbers 't tx ty tz qx qy qz qw'");
  EXPECT_EQ(error_of("0.0 0 0 0 0 0 0 1 5\n"), bad + ":1: expected 8 numbers 't tx ty tz qx qy qz qw'");
  std::filesystem::remove_all(dir);
}

// Commas separate fields as well as spaces and tabs (TUM's associate.py reads them so).
TEST(TrajectoryEval, ReadsCommaSeparatedLines) {
  const auto dir = std::filesystem::temp_directory_path() / "viqu_eval_commas";
  std::filesystem::create_directories(dir);
  const std::string spaces = (dir / "spaces.txt").string(), commas = (dir / "commas.txt").string();
  std::ofstream(spaces) << "1.5 0.25 -1 2 0 0 0.6 0.8\n1.6 0.5 -1\t2 0 0 0 1\n";
  std::ofstream(commas) << "1.5,0.25,-1,2,0,0,0.6,0.8\n1.6, 0.5, -1, 2, 0, 0, 0, 1\n";
  const Trajectory a = ReadTumTrajectory(spaces), b = ReadTumTrajectory(commas);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a[i].t_ns, b[i].t_ns);
    EXPECT_EQ(a[i].p_w_x, b[i].p_w_x);
    EXPECT_EQ(a[i].q_w_x.coeffs(), b[i].q_w_x.coeffs());
  }
  EXPECT_EQ(b[0].t_ns, 1500000000);
  EXPECT_DOUBLE_EQ(b[0].q_w_x.z(), 0.6);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace viqu::eval

// Tests of sim::ImuModel: white noise, bias random walk, initial biases, validation, determinism.
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/errors.h"
#include "sim/imu_model.h"

namespace viqu::sim {
namespace {

constexpr double kGravity = 9.81;  // (m/s^2)

int64_t SampleTimeNs(int k, double rate_hz) {  // time of the k-th sample, k >= 1 (ns)
  return static_cast<int64_t>(std::llround(1e9 * k / rate_hz));
}

// A tilted trunk standing still: R_w_i with roll, pitch and yaw all non-zero.
Eigen::Matrix3d TiltedR_w_i() {
  return (Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// Standing still for T = 60 s at 200 Hz (N = 12000 samples). Per axis, a reading is
//   y_k = truth + b_0 + w_k + n_k,  w_k = bias walk since the start, n_k ~ N(0, sigma^2).
// Mean over the run: mean(y) - truth - b_0 = mean(n) + mean(w), independent terms with
//   Var(mean n) = sigma^2 / N  and  Var(mean w) ~ Var((1/T) int_0^T W dt) = walk^2 T / 3
// (a Wiener process W with intensity walk^2). Bound: 4 standard deviations of their sum.
// Against the time average of the model's own bias (accel_bias()/gyro_bias() after each reading),
// only the white noise is left: bound 4 sigma / sqrt(N).
TEST(ImuModel, StandingStillTiltedReadsGravityInBodyAndGyroBias) {
  const ImuConfig cfg;  // defaults: 200 Hz, 0.02 m/s^2, 0.002 rad/s, walks 0.001 and 0.0001
  ImuBiasOptions bias;
  bias.accel_bias_i = Eigen::Vector3d::Zero();  // accel: "reads gravity" with no initial bias
  ImuModel imu(cfg, /*seed=*/42, bias);         // gyro: initial bias drawn from the seed
  const Eigen::Vector3d gyro_bias_0 = imu.gyro_bias();
  ASSERT_GT(gyro_bias_0.norm(), 0.0);

  const Eigen::Vector3d accel_true_i = TiltedR_w_i().transpose() * Eigen::Vector3d(0, 0, kGravity);
  const double T_s = 60.0;
  const int n = static_cast<int>(T_s * cfg.rate_hz);
  Eigen::Vector3d sum_accel = Eigen::Vector3d::Zero(), sum_gyro = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_accel_bias = Eigen::Vector3d::Zero(), sum_gyro_bias = Eigen::Vector3d::Zero();
  for (int k = 1; k <= n; ++k) {
    const ImuSample s = imu.Measure(SampleTimeNs(k, cfg.rate_hz), accel_true_i, Eigen::Vector3d::Zero());
    sum_accel += s.accel_i;
    sum_gyro += s.gyro_i;
    sum_accel_bias += imu.accel_bias();
    sum_gyro_bias += imu.gyro_bias();
  }
  const Eigen::Vector3d mean_accel = sum_accel / n, mean_gyro = sum_gyro / n;
  const Eigen::Vector3d mean_accel_bias = sum_accel_bias / n, mean_gyro_bias = sum_gyro_bias / n;

  const double accel_bound = 4.0 * std::sqrt(cfg.accel_noise * cfg.accel_noise / n +
                                             cfg.accel_bias_walk * cfg.accel_bias_walk * T_s / 3.0);
  const double gyro_bound = 4.0 * std::sqrt(cfg.gyro_noise * cfg.gyro_noise / n +
                                            cfg.gyro_bias_walk * cfg.gyro_bias_walk * T_s / 3.0);
  const double accel_noise_bound = 4.0 * cfg.accel_noise / std::sqrt(n);
  const double gyro_noise_bound = 4.0 * cfg.gyro_noise / std::sqrt(n);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(mean_accel[a], accel_true_i[a], accel_bound) << "axis " << a;
    EXPECT_NEAR(mean_gyro[a], gyro_bias_0[a], gyro_bound) << "axis " << a;
    EXPECT_NEAR(mean_accel[a] - mean_accel_bias[a], accel_true_i[a], accel_noise_bound) << "axis " << a;
    EXPECT_NEAR(mean_gyro[a] - mean_gyro_bias[a], 0.0, gyro_noise_bound) << "axis " << a;
  }
  EXPECT_NEAR(mean_accel.norm(), kGravity, std::sqrt(3.0) * accel_bound);
  std::printf("accel mean - g_i = (%.2e %.2e %.2e) m/s^2, bound %.2e\n",
              mean_accel[0] - accel_true_i[0], mean_accel[1] - accel_true_i[1],
              mean_accel[2] - accel_true_i[2], accel_bound);
  std::printf("gyro mean - b_g0 = (%.2e %.2e %.2e) rad/s, bound %.2e; b_g0 = (%.2e %.2e %.2e)\n",
              mean_gyro[0] - gyro_bias_0[0], mean_gyro[1] - gyro_bias_0[1],
              mean_gyro[2] - gyro_bias_0[2], gyro_bound, gyro_bias_0[0], gyro_bias_0[1],
              gyro_bias_0[2]);
}

// The residual y - truth - bias (the model's own bias after each reading) is the white noise;
// its sample std over N = 12000 x 3 values has a relative std of 1/sqrt(2 N) = 0.4%: 5% is a
// loose bound that still catches a wrong scale (e.g. noise * sqrt(dt)).
TEST(ImuModel, WhiteNoiseStdMatchesConfig) {
  ImuConfig cfg;
  cfg.accel_noise = 0.05;
  cfg.gyro_noise = 0.003;
  ImuModel imu(cfg, 7);
  const Eigen::Vector3d accel_true_i(0.3, -0.2, kGravity), gyro_true_i(0.1, 0.0, -0.05);
  double ss_accel = 0, ss_gyro = 0;
  const int n = 12000;
  for (int k = 1; k <= n; ++k) {
    const ImuSample s = imu.Measure(SampleTimeNs(k, cfg.rate_hz), accel_true_i, gyro_true_i);
    ss_accel += (s.accel_i - accel_true_i - imu.accel_bias()).squaredNorm();
    ss_gyro += (s.gyro_i - gyro_true_i - imu.gyro_bias()).squaredNorm();
  }
  const double std_accel = std::sqrt(ss_accel / (3.0 * n)), std_gyro = std::sqrt(ss_gyro / (3.0 * n));
  std::printf("accel noise std %.5f (config %.5f), gyro noise std %.6f (config %.6f)\n", std_accel,
              cfg.accel_noise, std_gyro, cfg.gyro_noise);
  EXPECT_NEAR(std_accel, cfg.accel_noise, 0.05 * cfg.accel_noise);
  EXPECT_NEAR(std_gyro, cfg.gyro_noise, 0.05 * cfg.gyro_noise);
}

// Bias variance after time T across many seeds, both walks, zero initial bias. With S seeds x 3
// axes = 1800 zero-mean values the variance estimate has a relative std of sqrt(2/1800) = 3.3%,
// so 15% is about 4.5 standard deviations. Checked at two times (linear growth) and at two rates
// (continuous-time units: the variance must not depend on the rate).
struct WalkVariance {
  double accel = 0, gyro = 0;  // mean squared bias per axis (m^2/s^4, rad^2/s^2)
};
WalkVariance BiasVarianceAfter(double T_s, double rate_hz, int seeds) {
  ImuConfig cfg;
  cfg.rate_hz = rate_hz;
  ImuBiasOptions zero;
  zero.accel_bias_i = Eigen::Vector3d::Zero();
  zero.gyro_bias_i = Eigen::Vector3d::Zero();
  WalkVariance v;
  const int n = static_cast<int>(std::lround(T_s * rate_hz));
  for (int s = 0; s < seeds; ++s) {
    ImuModel imu(cfg, 1000 + s, zero);
    for (int k = 1; k <= n; ++k) {
      imu.Measure(SampleTimeNs(k, rate_hz), Eigen::Vector3d(0, 0, kGravity), Eigen::Vector3d::Zero());
    }
    v.accel += imu.accel_bias().squaredNorm();
    v.gyro += imu.gyro_bias().squaredNorm();
  }
  v.accel /= 3.0 * seeds;
  v.gyro /= 3.0 * seeds;
  return v;
}

TEST(ImuModel, BiasWalkVarianceGrowsLinearlyInTime) {
  const ImuConfig cfg;
  const int seeds = 600;
  struct Case {
    double T_s, rate_hz;
  };
  for (const Case c : {Case{2.5, 200}, Case{10, 200}, Case{10, 50}}) {
    const WalkVariance v = BiasVarianceAfter(c.T_s, c.rate_hz, seeds);
    const double expect_accel = cfg.accel_bias_walk * cfg.accel_bias_walk * c.T_s;
    const double expect_gyro = cfg.gyro_bias_walk * cfg.gyro_bias_walk * c.T_s;
    std::printf("T %.1f s at %.0f Hz: accel bias var / walk^2 T = %.3f, gyro %.3f\n", c.T_s,
                c.rate_hz, v.accel / expect_accel, v.gyro / expect_gyro);
    EXPECT_NEAR(v.accel / expect_accel, 1.0, 0.15) << "T " << c.T_s << " rate " << c.rate_hz;
    EXPECT_NEAR(v.gyro / expect_gyro, 1.0, 0.15) << "T " << c.T_s << " rate " << c.rate_hz;
  }
}

TEST(ImuModel, InitialBiasesDrawnFromSeedOrFixed) {
  const ImuConfig cfg;
  ImuModel drawn(cfg, 3);
  EXPECT_GT(drawn.accel_bias().norm(), 0.0);
  EXPECT_GT(drawn.gyro_bias().norm(), 0.0);
  // Spread of the drawn biases over seeds matches the documented std (0.02, 0.002) within 5%
  // (6000 values per sensor: the std estimate has a relative std of 1/sqrt(12000) = 0.9%).
  double ss_a = 0, ss_g = 0;
  const int seeds = 2000;
  for (int s = 0; s < seeds; ++s) {
    ImuModel m(cfg, s);
    ss_a += m.accel_bias().squaredNorm();
    ss_g += m.gyro_bias().squaredNorm();
  }
  const ImuBiasOptions defaults;
  EXPECT_NEAR(std::sqrt(ss_a / (3 * seeds)), defaults.accel_bias_std, 0.05 * defaults.accel_bias_std);
  EXPECT_NEAR(std::sqrt(ss_g / (3 * seeds)), defaults.gyro_bias_std, 0.05 * defaults.gyro_bias_std);

  ImuBiasOptions fixed;
  fixed.accel_bias_i = Eigen::Vector3d(0.1, -0.2, 0.3);
  fixed.gyro_bias_i = Eigen::Vector3d(-0.01, 0.02, 0.0);
  ImuModel m(cfg, 3, fixed);
  EXPECT_EQ(m.accel_bias(), *fixed.accel_bias_i);
  EXPECT_EQ(m.gyro_bias(), *fixed.gyro_bias_i);
}

TEST(ImuModel, RejectsNonFiniteInputs) {
  ImuModel imu(ImuConfig{}, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(imu.Measure(1000, Eigen::Vector3d(0, nan, 9.81), Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(imu.Measure(1000, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d(inf, 0, 0)), InputError);
  // A rejected reading leaves the model as it was: the next good one is accepted.
  EXPECT_NO_THROW(imu.Measure(1000, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero()));
}

TEST(ImuModel, RejectsTimestampsThatDoNotIncrease) {
  ImuModel imu(ImuConfig{}, 1);
  imu.Measure(5'000'000, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero());
  EXPECT_THROW(imu.Measure(4'000'000, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(imu.Measure(5'000'000, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero()), InputError);
  EXPECT_NO_THROW(imu.Measure(10'000'000, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero()));
}

TEST(ImuModel, RejectsInvalidConfig) {
  ImuConfig bad_rate;
  bad_rate.rate_hz = 0;
  EXPECT_THROW(ImuModel(bad_rate, 1), InputError);
  ImuConfig bad_noise;
  bad_noise.gyro_noise = -1e-3;
  EXPECT_THROW(ImuModel(bad_noise, 1), InputError);
  ImuConfig bad_walk;
  bad_walk.accel_bias_walk = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ImuModel(bad_walk, 1), InputError);
}

std::vector<ImuSample> RunImu(uint64_t seed) {
  ImuModel imu(ImuConfig{}, seed);
  std::vector<ImuSample> out;
  for (int k = 1; k <= 200; ++k) {
    out.push_back(imu.Measure(SampleTimeNs(k, 200), Eigen::Vector3d(0.1, 0.2, 9.81),
                              Eigen::Vector3d(0.01, 0.0, 0.3)));
  }
  return out;
}

TEST(ImuModel, SameSeedIdenticalDifferentSeedDiffers) {
  const auto a = RunImu(11), b = RunImu(11), c = RunImu(12);
  ASSERT_EQ(a.size(), b.size());
  int differing = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].t_ns, b[k].t_ns);
    EXPECT_EQ(a[k].accel_i, b[k].accel_i);  // bitwise equal
    EXPECT_EQ(a[k].gyro_i, b[k].gyro_i);
    if (a[k].accel_i != c[k].accel_i && a[k].gyro_i != c[k].gyro_i) ++differing;
  }
  EXPECT_EQ(differing, static_cast<int>(a.size()));
}

}  // namespace
}  // namespace viqu::sim

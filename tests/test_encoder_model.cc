// Tests of sim::EncoderModel: noise, quantisation, finite-difference velocity, validation,
// determinism.
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "sim/encoder_model.h"

namespace viqu::sim {
namespace {

using Joints = std::array<double, kNumJoints>;
constexpr int64_t kDtNs = 5'000'000;  // 200 Hz (ns)

// Random true joint angles, uniform over a range much wider than the quantisation step, so the
// quantisation error is uniform on [-step/2, step/2] and independent of the noise.
Joints RandomJoints(std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  Joints q;
  for (double& v : q) v = u(*rng);
  return q;
}

TEST(EncoderModel, PositionsLieOnTheResolutionGrid) {
  JointsConfig cfg;
  cfg.resolution_rad = 0.0015;
  EncoderModel enc(cfg, 5);
  std::mt19937_64 truth(99);
  for (int k = 1; k <= 1000; ++k) {
    const JointState js = enc.Measure(k * kDtNs, RandomJoints(&truth), Joints{}, {});
    for (double p : js.position_rad) {
      const double steps = p / cfg.resolution_rad;
      EXPECT_NEAR(steps, std::round(steps), 1e-9);
    }
  }
}

// Error = noise + quantisation error, independent: std = sqrt(noise^2 + step^2 / 12).
// 20000 readings x 8 joints: the std estimate is good to well under 1%; the 10% bound allows for
// the uniform approximation of the quantisation error.
TEST(EncoderModel, ErrorStdMatchesNoiseAndQuantisation) {
  struct Case {
    double noise_rad, resolution_rad;
  };
  for (const Case c : {Case{0.001, 0.0015}, Case{0.001, 0.0}, Case{0.0, 0.002}, Case{0.0005, 0.004}}) {
    JointsConfig cfg;
    cfg.noise_rad = c.noise_rad;
    cfg.resolution_rad = c.resolution_rad;
    EncoderModel enc(cfg, 21);
    std::mt19937_64 truth(1);
    double sum = 0, ss = 0;
    const int n = 20000;
    for (int k = 1; k <= n; ++k) {
      const Joints q = RandomJoints(&truth);
      const JointState js = enc.Measure(k * kDtNs, q, Joints{}, {});
      for (int j = 0; j < kNumJoints; ++j) {
        const double e = js.position_rad[j] - q[j];
        sum += e;
        ss += e * e;
      }
    }
    const double m = n * kNumJoints;
    const double mean = sum / m, std = std::sqrt(ss / m - mean * mean);
    const double expect = std::sqrt(c.noise_rad * c.noise_rad + c.resolution_rad * c.resolution_rad / 12);
    std::printf("noise %.4f step %.4f: error mean %.2e std %.4e rad, expected std %.4e (ratio %.3f)\n",
                c.noise_rad, c.resolution_rad, mean, std, expect, std / expect);
    EXPECT_NEAR(std, expect, 0.10 * expect);
    EXPECT_NEAR(mean, 0.0, 4 * expect / std::sqrt(m));
  }
}

TEST(EncoderModel, VelocityIsFiniteDifferenceOfMeasuredPositions) {
  EncoderModel enc(JointsConfig{}, 8);
  Joints q{}, qd{};
  for (int j = 0; j < kNumJoints; ++j) qd[j] = 0.1 * (j + 1);
  const JointState first = enc.Measure(kDtNs, q, qd, {});
  EXPECT_EQ(first.velocity_rad_s, qd);  // no predecessor: the true velocity
  JointState prev = first;
  for (int k = 2; k < 50; ++k) {
    for (int j = 0; j < kNumJoints; ++j) q[j] += qd[j] * 0.007;
    const int64_t t = kDtNs + (k - 1) * 7'000'000;  // 7 ms steps: dt comes from the timestamps
    const JointState js = enc.Measure(t, q, qd, {});
    for (int j = 0; j < kNumJoints; ++j) {
      EXPECT_DOUBLE_EQ(js.velocity_rad_s[j], (js.position_rad[j] - prev.position_rad[j]) / 0.007);
    }
    prev = js;
  }
}

TEST(EncoderModel, PassesContactsAndTimeThrough) {
  EncoderModel enc(JointsConfig{}, 8);
  const std::array<bool, kNumLegs> contact{true, false, false, true};
  const JointState js = enc.Measure(123456789, Joints{}, Joints{}, contact);
  EXPECT_EQ(js.contact, contact);
  EXPECT_EQ(js.t_ns, 123456789);
}

TEST(EncoderModel, RejectsNonFiniteInputsAndTimestampsThatDoNotIncrease) {
  EncoderModel enc(JointsConfig{}, 8);
  Joints bad{};
  bad[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(enc.Measure(kDtNs, bad, Joints{}, {}), InputError);
  EXPECT_THROW(enc.Measure(kDtNs, Joints{}, bad, {}), InputError);
  EXPECT_NO_THROW(enc.Measure(kDtNs, Joints{}, Joints{}, {}));
  EXPECT_THROW(enc.Measure(kDtNs, Joints{}, Joints{}, {}), InputError);
  EXPECT_THROW(enc.Measure(kDtNs - 1, Joints{}, Joints{}, {}), InputError);
  EXPECT_NO_THROW(enc.Measure(2 * kDtNs, Joints{}, Joints{}, {}));
}

TEST(EncoderModel, RejectsInvalidConfig) {
  JointsConfig c1;
  c1.rate_hz = -5;
  EXPECT_THROW(EncoderModel(c1, 1), InputError);
  JointsConfig c2;
  c2.noise_rad = -0.1;
  EXPECT_THROW(EncoderModel(c2, 1), InputError);
  JointsConfig c3;
  c3.resolution_rad = std::numeric_limits<double>::infinity();
  EXPECT_THROW(EncoderModel(c3, 1), InputError);
}

std::vector<JointState> RunEncoder(uint64_t seed) {
  EncoderModel enc(JointsConfig{}, seed);
  std::mt19937_64 truth(3);
  std::vector<JointState> out;
  for (int k = 1; k <= 100; ++k) out.push_back(enc.Measure(k * kDtNs, RandomJoints(&truth), Joints{}, {}));
  return out;
}

TEST(EncoderModel, SameSeedIdenticalDifferentSeedDiffers) {
  const auto a = RunEncoder(4), b = RunEncoder(4), c = RunEncoder(5);
  int differing = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].position_rad, b[k].position_rad);
    EXPECT_EQ(a[k].velocity_rad_s, b[k].velocity_rad_s);
    if (a[k].position_rad != c[k].position_rad) ++differing;
  }
  EXPECT_GT(differing, 90);  // some readings may quantise alike by chance, not most
}

}  // namespace
}  // namespace viqu::sim

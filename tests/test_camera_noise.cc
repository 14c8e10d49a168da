// Tests of sim::AddPixelNoise: noise level, saturation, determinism, validation.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "common/errors.h"
#include "sim/camera_noise.h"

namespace viqu::sim {
namespace {

// On mid-grey (far from both limits) the output noise is the rounded Gaussian, whose std is
// sqrt(std^2 + 1/12) (Sheppard's correction). A 640x480x3 image gives 921600 values: the std
// estimate is good to 0.1%, so 2% is a tight check of the scale.
TEST(CameraNoise, NoiseStdMatchesConfigPerChannel) {
  for (const double noise_std : {2.0, 5.0}) {
    cv::Mat img(480, 640, CV_8UC3, cv::Scalar::all(128));
    std::mt19937_64 rng(17);
    AddPixelNoise(&img, noise_std, &rng);
    cv::Mat diff;
    img.convertTo(diff, CV_64FC3, 1.0, -128.0);
    cv::Scalar mean, stddev;
    cv::meanStdDev(diff, mean, stddev);
    const double expect = std::sqrt(noise_std * noise_std + 1.0 / 12.0);
    for (int c = 0; c < 3; ++c) {
      std::printf("std %.1f channel %d: mean %.4f std %.4f (expected %.4f)\n", noise_std, c, mean[c],
                  stddev[c], expect);
      EXPECT_NEAR(stddev[c], expect, 0.02 * expect);
      EXPECT_NEAR(mean[c], 0.0, 0.02);
    }
    // Channels are independent: correlation of R and G noise near zero.
    std::vector<cv::Mat> ch;
    cv::split(diff, ch);
    const double corr = (ch[0].dot(ch[1]) / ch[0].total()) / (expect * expect);
    EXPECT_NEAR(corr, 0.0, 0.01);
  }
}

// Expected mean of max(0, round(n)) and P(round(n) > 0) for n ~ N(0, std^2): what the black
// image must show if the sum saturates at 0 instead of wrapping around.
double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double ClippedRoundedMean(double noise_std) {
  double m = 0;
  for (int k = 1; k < 255; ++k) m += k * (Phi((k + 0.5) / noise_std) - Phi((k - 0.5) / noise_std));
  return m;
}

// At 0 and 255 the sum saturates instead of wrapping: on black no pixel jumps near 255, the
// fraction above 0 is P(n >= 0.5) and the mean is E[max(0, round(n))] (0.40 and 0.79 for std 2);
// white mirrors black. 921600 values: sampling error of the mean ~0.001, of the fraction ~0.0005.
TEST(CameraNoise, SaturatesAtBlackAndWhite) {
  const double noise_std = 2.0;
  std::mt19937_64 rng(3);
  cv::Mat black(480, 640, CV_8UC3, cv::Scalar::all(0));
  cv::Mat white(480, 640, CV_8UC3, cv::Scalar::all(255));
  AddPixelNoise(&black, noise_std, &rng);
  AddPixelNoise(&white, noise_std, &rng);
  double min_v, max_v;
  cv::minMaxLoc(black.reshape(1), &min_v, &max_v);
  EXPECT_EQ(min_v, 0);
  EXPECT_LE(max_v, 6 * noise_std);  // no wrap-around to 255
  cv::minMaxLoc(white.reshape(1), &min_v, &max_v);
  EXPECT_EQ(max_v, 255);
  EXPECT_GE(min_v, 255 - 6 * noise_std);
  const double n = static_cast<double>(black.total() * 3);
  const double black_mean = cv::mean(black.reshape(1))[0];
  const double white_mean = cv::mean(white.reshape(1))[0];
  const double black_above = cv::countNonZero(black.reshape(1)) / n;
  const double expect_mean = ClippedRoundedMean(noise_std), expect_above = 1 - Phi(0.5 / noise_std);
  std::printf("black: mean %.4f above0 %.4f; white: 255-mean %.4f; expected %.4f and %.4f\n",
              black_mean, black_above, 255 - white_mean, expect_mean, expect_above);
  EXPECT_NEAR(black_mean, expect_mean, 0.01);
  EXPECT_NEAR(255 - white_mean, expect_mean, 0.01);
  EXPECT_NEAR(black_above, expect_above, 0.005);
}

TEST(CameraNoise, SameGeneratorStateIdenticalDifferentSeedDiffers) {
  cv::Mat base(480, 640, CV_8UC3);
  cv::randu(base, 0, 256);  // any content; this generator does not affect the noise
  cv::Mat a = base.clone(), b = base.clone(), c = base.clone();
  std::mt19937_64 ra(5), rb(5), rc(6);
  AddPixelNoise(&a, 2.0, &ra);
  AddPixelNoise(&b, 2.0, &rb);
  AddPixelNoise(&c, 2.0, &rc);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0.0);
  // The generator advances by exactly one draw per call.
  std::mt19937_64 expect(5);
  expect();
  EXPECT_EQ(ra, expect);
  // cv::theRNG does not influence the result.
  cv::theRNG().state = 12345;
  cv::Mat d = base.clone();
  std::mt19937_64 rd(5);
  AddPixelNoise(&d, 2.0, &rd);
  EXPECT_EQ(cv::norm(a, d, cv::NORM_L1), 0.0);
}

// The run loop draws the noise on the simulation thread and adds it on the estimator's: the two
// steps give the same bytes and the same generator state as one call, for each image in turn.
TEST(CameraNoise, DrawnThenAppliedEqualsAddedAtOnce) {
  cv::Mat base(480, 640, CV_8UC3);
  cv::randu(base, 0, 256);
  std::mt19937_64 once(9), split(9);
  for (int k = 0; k < 3; ++k) {
    cv::Mat a = base.clone(), b = base.clone();
    AddPixelNoise(&a, 2.0, &once);
    const PixelNoiseDraw draw = DrawPixelNoise(2.0, &split);
    EXPECT_EQ(once, split) << k;
    EXPECT_EQ(cv::norm(base, b, cv::NORM_L1), 0.0);  // drawing touches no image
    ApplyPixelNoise(draw, &b);
    EXPECT_EQ(cv::norm(a, b, cv::NORM_L1), 0.0) << k;
    EXPECT_GT(cv::norm(a, base, cv::NORM_L1), 0.0) << k;
  }
  // No noise: no draw, no change.
  const PixelNoiseDraw none = DrawPixelNoise(0.0, &split);
  EXPECT_EQ(once, split);
  cv::Mat c = base.clone();
  ApplyPixelNoise(none, &c);
  EXPECT_EQ(cv::norm(base, c, cv::NORM_L1), 0.0);
  EXPECT_THROW(DrawPixelNoise(-1.0, &split), InputError);
  EXPECT_THROW(DrawPixelNoise(std::nan(""), &split), InputError);
  cv::Mat f32(20, 20, CV_32FC3, cv::Scalar::all(0.5));
  EXPECT_THROW(ApplyPixelNoise(DrawPixelNoise(2.0, &split), &f32), InputError);
}

TEST(CameraNoise, WorksOnRoiAndSingleChannelOnly8Bit) {
  cv::Mat big(100, 100, CV_8UC3, cv::Scalar::all(100));
  cv::Mat roi = big(cv::Rect(10, 10, 50, 50));
  std::mt19937_64 rng(1);
  AddPixelNoise(&roi, 3.0, &rng);
  EXPECT_GT(cv::norm(roi, cv::Mat(50, 50, CV_8UC3, cv::Scalar::all(100)), cv::NORM_L1), 0.0);
  EXPECT_EQ(big.at<cv::Vec3b>(5, 5), cv::Vec3b(100, 100, 100));  // outside the ROI untouched
  cv::Mat grey(20, 20, CV_8UC1, cv::Scalar::all(50));
  AddPixelNoise(&grey, 3.0, &rng);
  EXPECT_GT(cv::norm(grey, cv::Mat(20, 20, CV_8UC1, cv::Scalar::all(50)), cv::NORM_L1), 0.0);
  cv::Mat f32(20, 20, CV_32FC3, cv::Scalar::all(0.5));
  EXPECT_THROW(AddPixelNoise(&f32, 3.0, &rng), InputError);
}

TEST(CameraNoise, ZeroStdIsNoOpAndNegativeStdThrows) {
  cv::Mat img(20, 20, CV_8UC3, cv::Scalar::all(77));
  std::mt19937_64 rng(1), untouched(1);
  AddPixelNoise(&img, 0.0, &rng);
  EXPECT_EQ(cv::norm(img, cv::Mat(20, 20, CV_8UC3, cv::Scalar::all(77)), cv::NORM_L1), 0.0);
  EXPECT_EQ(rng, untouched);
  EXPECT_THROW(AddPixelNoise(&img, -1.0, &rng), InputError);
  EXPECT_THROW(AddPixelNoise(nullptr, 1.0, &rng), InputError);
  EXPECT_THROW(AddPixelNoise(&img, 1.0, nullptr), InputError);
}

}  // namespace
}  // namespace viqu::sim

// Tests of sim::DepthToSteps and sim::QuantiseDepth: the steps are std::round of depth times the
// scale (checked against that formula, including exact halves and the range ends), and the
// quantised depth is what a reader gets back from the steps.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "common/errors.h"
#include "sim/depth_quantisation.h"

namespace viqu::sim {
namespace {

// The definition: round half away from zero, 0 where that is not in [1, 65535] or not finite.
uint16_t ReferenceStep(float depth_m, double steps_per_m) {
  const double v = std::round(static_cast<double>(depth_m) * steps_per_m);
  return (std::isfinite(v) && v > 0 && v <= 65535) ? static_cast<uint16_t>(v) : 0;
}

TEST(DepthToSteps, EqualsRoundingOfDepthTimesScale) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  // Exact halves at 4096 steps per metre (a power of two: (k + 0.5) / 4096 is a float), the
  // range ends, values just around them, and what is not depth.
  std::vector<float> values = {0.5f / 4096, 2.5f / 4096, 65535.5f / 4096, 65534.5f / 4096,0.0f, -0.0f, -1.0f, inf, -inf, nan, 1e-9f, 0.5f / 5000, 0.4999f / 5000,
                               65535.0f / 5000, 65535.4f / 5000, 65535.5f / 5000, 65536.0f / 5000, 13.5f,
                               1e30f, std::nextafter(0.5f / 5000, 0.0f), std::nextafter(0.5f / 5000, 1.0f)};
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<float> depth(0.0f, 14.0f);
  for (int i = 0; i < 20000; ++i) values.push_back(depth(rng));
  for (int k = 0; k < 2000; ++k) values.push_back((k + 0.5f) / 5000.0f);
  cv::Mat d(1, static_cast<int>(values.size()), CV_32F);
  for (size_t i = 0; i < values.size(); ++i) d.at<float>(0, static_cast<int>(i)) = values[i];
  for (const double scale : {5000.0, 1000.0, 1.0 / 0.0002, 4096.0, 333.3}) {
    const cv::Mat steps = DepthToSteps(d, scale);
    ASSERT_EQ(steps.type(), CV_16U);
    int differ = 0;
    for (size_t i = 0; i < values.size(); ++i) {
      differ += steps.at<uint16_t>(0, static_cast<int>(i)) != ReferenceStep(values[i], scale);
    }
    EXPECT_EQ(differ, 0) << "scale " << scale;
  }
  const cv::Mat at_4096 = DepthToSteps(d, 4096);
  EXPECT_EQ(at_4096.at<uint16_t>(0, 0), 1);      // halves round away from zero
  EXPECT_EQ(at_4096.at<uint16_t>(0, 1), 3);      // (not to even)
  EXPECT_EQ(at_4096.at<uint16_t>(0, 2), 0);      // 65535.5 steps is past the range
  EXPECT_EQ(at_4096.at<uint16_t>(0, 3), 65535);  // 65534.5 steps is the last one
  EXPECT_THROW(DepthToSteps(cv::Mat(2, 2, CV_64F, cv::Scalar(1.0)), 5000), RunError);
}

TEST(QuantiseDepth, ReturnsTheStepsAndTheDepthAReaderGetsBack) {
  cv::Mat d(48, 64, CV_32F);
  cv::randu(d, cv::Scalar(-1.0), cv::Scalar(15.0));
  d.at<float>(3, 3) = std::numeric_limits<float>::quiet_NaN();
  const cv::Mat original = d.clone();
  const cv::Mat steps = QuantiseDepth(&d, 5000);
  ASSERT_EQ(steps.type(), CV_16U);
  EXPECT_EQ(cv::norm(steps, DepthToSteps(original, 5000), cv::NORM_INF), 0.0);
  cv::Mat read_back;
  steps.convertTo(read_back, CV_32F, 1.0 / 5000);  // what the dataset readers do
  EXPECT_EQ(cv::norm(d, read_back, cv::NORM_INF), 0.0);
  EXPECT_EQ(d.at<float>(3, 3), 0.0f);
  EXPECT_EQ(DepthToSteps(d, 5000).at<uint16_t>(10, 10), steps.at<uint16_t>(10, 10));  // idempotent
  cv::Mat empty;
  EXPECT_TRUE(QuantiseDepth(&empty, 5000).empty());
}

TEST(DepthStepsToWrite, GivenStepsAreWrittenAsTheyAreOthersConverted) {
  cv::Mat d(6, 8, CV_32F, cv::Scalar(1.25f));
  const cv::Mat given = DepthToSteps(d, 5000);
  EXPECT_EQ(DepthStepsToWrite(d, given, 5000, "R").data, given.data);  // no copy, no conversion
  const cv::Mat converted = DepthStepsToWrite(d, cv::Mat(), 5000, "R");
  EXPECT_EQ(cv::norm(converted, given, cv::NORM_INF), 0.0);
  try {
    DepthStepsToWrite(d, cv::Mat(6, 8, CV_32F, cv::Scalar(0)), 5000, "TumRecorder");
    FAIL() << "a float image is not steps";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("TumRecorder"), std::string::npos) << e.what();
  }
  EXPECT_THROW(DepthStepsToWrite(d, cv::Mat(5, 8, CV_16U, cv::Scalar(0)), 5000, "R"), RunError);
}

}  // namespace
}  // namespace viqu::sim

// The paper's eqs. 1-4 (slam/core/dynamic_attribute.h) on inputs worked by hand.
#include "slam/core/dynamic_attribute.h"

#include <gtest/gtest.h>

namespace viqu::slam {
namespace {

constexpr int64_t kFrameNs = 100'000'000;  // 10 Hz

TEST(DynamicAttribute, Eq1MeanMaskDepthIgnoresFeaturesWithoutDepth) {
  EXPECT_DOUBLE_EQ(MeanMaskDepth({1.0f, 2.0f, -1.0f, 3.0f}), 2.0);
  EXPECT_DOUBLE_EQ(MeanMaskDepth({-1.0f}), 0.0);
  EXPECT_DOUBLE_EQ(MeanMaskDepth({}), 0.0);
}

TEST(DynamicAttribute, Eq2HalfWindowChange) {
  EXPECT_DOUBLE_EQ(HalfWindowChange({1, 2, 3, 4}), 2.0);     // (3+4)/2 - (1+2)/2
  EXPECT_DOUBLE_EQ(HalfWindowChange({1, 2, 3, 4, 5}), 3.0);  // (4+5)/2 - (1+2)/2: the middle one is in neither half
  EXPECT_DOUBLE_EQ(HalfWindowChange({4, 1}), -3.0);
  EXPECT_DOUBLE_EQ(HalfWindowChange({7}), 0.0);
}

TEST(DynamicAttribute, Eq3WeightsAndPrior) {
  EXPECT_DOUBLE_EQ(DynamicAttribute(0.2, 0.1, 1.0, 1.0, 1.0, 0.5), 0.8);
  EXPECT_DOUBLE_EQ(DynamicAttribute(0.2, 0.1, 1.0, 2.0, 0.0, 0.0), 0.4);
  CategoryPriors p;
  p.person = 0.9;
  p.box = 0.2;
  EXPECT_DOUBLE_EQ(CategoryPrior(Category::kPerson, p), 0.9);
  EXPECT_DOUBLE_EQ(CategoryPrior(Category::kBox, p), 0.2);
  EXPECT_DOUBLE_EQ(CategoryPrior(Category::kFurniture, p), 0.0);
}

DynamicSettings PaperSettings(double th_d) {
  DynamicSettings s;
  s.method = "paper";
  s.alpha = 1;
  s.beta = 1;
  s.gamma = 0.5;
  s.th_d = th_d;
  s.window_s = 0.3;  // 4 frames at 10 Hz: t-0.3 ... t
  s.window_n = 4;
  return s;
}

// w_bar = 0.5 t^2 (1 m/s^2), d_bar constant: eq. 2 gives dw = 0.2 t - 0.03 over four frames,
// eq. 4 over four values of A gives dA = 0.2 * 0.2 = 0.04 m, whatever the prior.
double DeltaAOfAcceleratingObject(double th_d, bool* dynamic) {
  PaperAttributeSeries series;
  const DynamicSettings s = PaperSettings(th_d);
  for (int k = 0; k <= 12; ++k) {
    const double t = 0.1 * k;
    *dynamic = series.Add(k * kFrameNs, 1.0 + 0.5 * t * t, 2.0, 1.0, s);
  }
  return series.last_delta_a();
}

TEST(DynamicAttribute, Eq4AcceleratingObjectWorkedByHand) {
  bool dynamic = false;
  EXPECT_NEAR(DeltaAOfAcceleratingObject(0.03, &dynamic), 0.04, 1e-9);
  EXPECT_TRUE(dynamic);
  EXPECT_NEAR(DeltaAOfAcceleratingObject(0.05, &dynamic), 0.04, 1e-9);
  EXPECT_FALSE(dynamic);
}

// The literal form's known weaknesses, which the README reports: an object at constant speed
// has a constant eq. 2 change, so eq. 4 gives 0 however fast it goes; the prior cancels; an
// approaching object gives a negative change.
TEST(DynamicAttribute, Eq4ConstantSpeedAndPriorCancel) {
  for (double prior : {0.0, 1.0}) {
    PaperAttributeSeries series;
    bool dynamic = true;
    for (int k = 0; k <= 12; ++k) dynamic = series.Add(k * kFrameNs, 1.0 + 2.0 * 0.1 * k, 2.0, prior, PaperSettings(0.01));
    EXPECT_FALSE(dynamic);
    EXPECT_NEAR(series.last_delta_a(), 0.0, 1e-9);
  }
  PaperAttributeSeries approaching;
  bool dynamic = true;
  for (int k = 0; k <= 12; ++k) {
    const double t = 0.1 * k;
    dynamic = approaching.Add(k * kFrameNs, 3.0, 3.0 - 0.5 * t * t, 1.0, PaperSettings(0.01));
  }
  EXPECT_FALSE(dynamic);
  EXPECT_NEAR(approaching.last_delta_a(), -0.04, 1e-9);
}

TEST(DynamicAttribute, FramesWithoutPointsOrDepthAreSkipped) {
  PaperAttributeSeries series;
  const DynamicSettings s = PaperSettings(0.03);
  bool dynamic = false;
  for (int k = 0; k <= 12; ++k) {
    const double t = 0.1 * k;
    dynamic = series.Add(k * kFrameNs, 1.0 + 0.5 * t * t, 2.0, 1.0, s);
  }
  ASSERT_TRUE(dynamic);
  EXPECT_TRUE(series.Add(13 * kFrameNs, 0.0, 2.0, 1.0, s));  // no labelled point: decision kept
  EXPECT_TRUE(series.Add(14 * kFrameNs, 2.0, 0.0, 1.0, s));  // no depth: decision kept
}

}  // namespace
}  // namespace viqu::slam

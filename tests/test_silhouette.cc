// Silhouettes in the instance image and their motion across the view (slam/core/silhouette.h),
// on hand-drawn masks with shifts worked out by hand.
#include "slam/core/silhouette.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace viqu::slam {
namespace {

constexpr int kBorderPx = 40;

StereoCamera Camera() {
  StereoCamera c;
  c.width = 640;
  c.height = 480;
  c.fx = c.fy = 343.0;
  c.cx = 319.5;
  c.cy = 239.5;
  c.bf = c.fx * 0.04;
  return c;
}

cv::Mat Blank() { return cv::Mat(480, 640, CV_16U, cv::Scalar(0)); }

// Columns [x0, x1] and rows [y0, y1], inclusive.
void Fill(cv::Mat* m, uint16_t id, int x0, int x1, int y0, int y1) {
  (*m)(cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1)).setTo(cv::Scalar(id));
}

Silhouette Of(const cv::Mat& m, uint16_t id, const Eigen::Isometry3d& T_c_w = Eigen::Isometry3d::Identity()) {
  std::map<uint16_t, Silhouette> all = ExtractSilhouettes(m, {3, 4, 5}, kBorderPx);
  Silhouette s = all[id];
  s.T_c_w = T_c_w;
  return s;
}

TEST(Silhouette, KeepsTheEndsThatBorderTheBackgroundAwayFromTheImageEdges) {
  cv::Mat m = Blank();
  Fill(&m, 3, 100, 199, 100, 299);
  Fill(&m, 4, 200, 259, 200, 299);  // meets 3's right side in rows 200-299
  Fill(&m, 5, 10, 60, 100, 149);    // its left side within 40 px of the image's edge
  const std::map<uint16_t, Silhouette> all = ExtractSilhouettes(m, {3, 4, 5}, kBorderPx);
  ASSERT_EQ(all.size(), 3u);
  const Silhouette& s3 = all.at(3);
  ASSERT_EQ(s3.v.size(), 100u);  // rows 100, 102, ..., 298
  EXPECT_EQ(s3.v.front(), 100);
  EXPECT_EQ(s3.v.back(), 298);
  for (size_t k = 0; k < s3.v.size(); ++k) {
    EXPECT_EQ(s3.lo[k], 100);
    EXPECT_EQ(s3.hi[k], s3.v[k] < 200 ? 199 : -1) << s3.v[k];  // the end that meets 4 does not count
  }
  EXPECT_TRUE(s3.touches_lo.empty());
  EXPECT_EQ(s3.touches_hi, std::vector<uint16_t>({4}));
  EXPECT_EQ(s3.frame_ids, std::vector<uint16_t>({3, 4, 5}));
  const Silhouette& s4 = all.at(4);
  EXPECT_EQ(s4.lo.front(), -1);
  EXPECT_EQ(s4.hi.front(), 259);
  const Silhouette& s5 = all.at(5);
  ASSERT_EQ(s5.v.size(), 25u);
  EXPECT_EQ(s5.lo.front(), -1);  // at the image's edge
  EXPECT_EQ(s5.hi.front(), 60);
  EXPECT_EQ(s3.RowIndex(150), 25);
  EXPECT_EQ(s3.RowIndex(151), -1);
}

// An end that meets an instance farther away is the object's own edge (it hides that one); one that
// meets a nearer instance, or one whose depth is unknown, may be where that one hides it.
TEST(Silhouette, AnEndInFrontOfAFartherInstanceCounts) {
  cv::Mat m = Blank();
  Fill(&m, 3, 100, 199, 100, 199);
  Fill(&m, 4, 200, 259, 100, 199);
  const auto right_end = [&](const std::map<uint16_t, double>& depth) {
    const Silhouette s = ExtractSilhouettes(m, {3, 4}, kBorderPx, depth, 0.3).at(3);
    EXPECT_EQ(s.touches_hi.empty(), s.hi.front() >= 0);
    return s.hi.front();
  };
  EXPECT_EQ(right_end({{3, 1.0}, {4, 2.0}}), 199);  // 4 stands 1 m behind
  EXPECT_EQ(right_end({{3, 1.0}, {4, 1.2}}), -1);   // within 0.3 m: which hides which is not known
  EXPECT_EQ(right_end({{3, 2.0}, {4, 1.0}}), -1);   // 4 in front
  EXPECT_EQ(right_end({{3, 1.0}}), -1);             // 4 without a depth
  EXPECT_EQ(right_end({}), -1);
}

// A box 2 m ahead; the camera steps 5 cm to the right, so a standing box moves left in the image
// by fx * 0.05 / 2 = 8.575 px. Drawn 9 px left, it shows 0.425 px of motion (the drawing's
// rounding); drawn 4 px left, it moved 4.575 px to the right.
TEST(Silhouette, TakesTheCamerasMotionOut) {
  const StereoCamera cam = Camera();
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = Eigen::Vector3d(-0.05, 0, 0);  // world to camera: the camera at x = +0.05 m
  cv::Mat ref = Blank(), stood = Blank(), walked = Blank();
  Fill(&ref, 3, 300, 379, 150, 349);
  Fill(&stood, 3, 291, 370, 150, 349);
  Fill(&walked, 3, 296, 375, 150, 349);
  const SilhouetteShift still = MeasureSilhouetteShift(Of(ref, 3), 2.0, Of(stood, 3, moved), cam, 10);
  EXPECT_TRUE(still.two_sided);
  EXPECT_EQ(still.rows, 200);  // 100 rows, both ends
  EXPECT_NEAR(still.shift_px, -9 + 8.575, 1e-6);
  EXPECT_NEAR(still.std_error_px, 0.0, 1e-9);
  const SilhouetteShift step = MeasureSilhouetteShift(Of(ref, 3), 2.0, Of(walked, 3, moved), cam, 10);
  EXPECT_NEAR(step.shift_px, -4 + 8.575, 1e-6);
  // A camera turned by 1 degree about its vertical axis moves everything by about fx * 1 deg.
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() = Eigen::AngleAxisd(1.0 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const SilhouetteShift unexplained = MeasureSilhouetteShift(Of(ref, 3), 2.0, Of(ref, 3, turned), cam, 10);
  EXPECT_LT(unexplained.shift_px, -5.5);  // the mask stayed where the turn would have moved it by +6 px
  EXPECT_GT(unexplained.shift_px, -6.5);
}

// A detector's mask grows by 2 px: with both sides seen this is no motion; one side alone shows it
// as 2 px and says it is one-sided.
TEST(Silhouette, BothSidesCancelTheMasksGrowth) {
  const StereoCamera cam = Camera();
  cv::Mat ref = Blank(), grown = Blank();
  Fill(&ref, 3, 300, 379, 150, 349);
  Fill(&grown, 3, 298, 381, 150, 349);
  const SilhouetteShift both = MeasureSilhouetteShift(Of(ref, 3), 1.5, Of(grown, 3), cam, 10);
  EXPECT_TRUE(both.two_sided);
  EXPECT_NEAR(both.shift_px, 0.0, 1e-6);
  Fill(&ref, 4, 380, 420, 150, 349);    // another object meets the right side in both frames
  Fill(&grown, 4, 382, 420, 150, 349);
  const SilhouetteShift left = MeasureSilhouetteShift(Of(ref, 3), 1.5, Of(grown, 3), cam, 10);
  EXPECT_FALSE(left.two_sided);
  EXPECT_EQ(left.rows, 100);
  EXPECT_NEAR(left.shift_px, -2.0, 1e-6);
  // Too few ends on a side: nothing to compare.
  EXPECT_EQ(MeasureSilhouetteShift(Of(ref, 3), 1.5, Of(grown, 3), cam, 101).rows, 0);
}

// A neighbour that the detector missed in one frame leaves background where it met the object: a
// false free end. The side it meets is left out of the comparison; the other side still counts.
TEST(Silhouette, AMissingNeighbourLeavesItsSideOut) {
  const StereoCamera cam = Camera();
  cv::Mat ref = Blank(), cur = Blank();
  Fill(&ref, 3, 300, 379, 150, 349);
  Fill(&ref, 4, 380, 420, 150, 249);  // meets the upper half of 3's right side
  Fill(&cur, 3, 306, 379, 150, 349);  // 4 missed; 3's left side 6 px to the right
  for (const bool ref_first : {true, false}) {
    const SilhouetteShift s = ref_first ? MeasureSilhouetteShift(Of(ref, 3), 1.5, Of(cur, 3), cam, 10)
                                        : MeasureSilhouetteShift(Of(cur, 3), 1.5, Of(ref, 3), cam, 10);
    EXPECT_EQ(s.rows, 100);  // the left ends alone
    EXPECT_FALSE(s.two_sided);
    EXPECT_NEAR(s.shift_px, ref_first ? 6.0 : -6.0, 1e-6);
  }
  Fill(&cur, 4, 380, 420, 150, 249);  // detected again: both sides, 3's left end moved 6 px
  const SilhouetteShift both = MeasureSilhouetteShift(Of(ref, 3), 1.5, Of(cur, 3), cam, 10);
  EXPECT_EQ(both.rows, 150);  // 100 left ends, 50 right ends below 4
  EXPECT_TRUE(both.two_sided);
  EXPECT_NEAR(both.shift_px, 3.0, 1e-6);
  // Met on both sides by instances the other frame lacks: nothing is compared.
  Fill(&ref, 5, 280, 299, 150, 349);
  cv::Mat alone = Blank();
  Fill(&alone, 3, 300, 379, 150, 349);
  EXPECT_EQ(MeasureSilhouetteShift(Of(ref, 3), 1.5, Of(alone, 3), cam, 10).rows, 0);
  EXPECT_EQ(MeasureSilhouetteShift(Of(alone, 3), 1.5, Of(ref, 3), cam, 10).rows, 0);
}

}  // namespace
}  // namespace viqu::slam

// Tests of sim::SegmentationModel: misses, dilation, latency, determinism, validation.
#include <cstdio>
#include <set>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"
#include "sim/segmentation_model.h"

namespace viqu::sim {
namespace {

SegmentationConfig Config(double miss_rate, int dilate_px, int latency_frames) {
  SegmentationConfig c;
  c.miss_rate = miss_rate;
  c.dilate_px = dilate_px;
  c.latency_frames = latency_frames;
  return c;
}

SegmentInstance Instance(uint16_t id, Category category) {
  SegmentInstance s;
  s.id = id;
  s.category = category;
  s.name = std::string(CategoryName(category)) + ":" + std::to_string(id);
  return s;
}

StereoFrame EmptyFrame(int width, int height) {
  StereoFrame f;
  f.left_instance_id = cv::Mat::zeros(height, width, CV_16UC1);
  f.instances.push_back(Instance(0, Category::kBackground));
  return f;
}

void AddRect(StereoFrame* f, uint16_t id, Category category, const cv::Rect& r) {
  f->left_instance_id(r).setTo(id);
  f->instances.push_back(Instance(id, category));
}

bool Listed(const StereoFrame& f, uint16_t id) {
  for (const auto& s : f.instances) {
    if (s.id == id) return true;
  }
  return false;
}

int CountId(const StereoFrame& f, uint16_t id) {
  return cv::countNonZero(f.left_instance_id == id);
}

// Five detectable instances per frame, miss rate 0.1, 4000 frames = 20000 Bernoulli trials: the
// observed rate has std sqrt(0.1 * 0.9 / 20000) = 0.0021, bound 4 std = 0.0085.
TEST(SegmentationModel, MissRateMatchesConfigAndOnlyDetectableInstancesAreDropped) {
  const double miss_rate = 0.1;
  SegmentationModel model(Config(miss_rate, 0, 0), 77);
  const std::vector<Category> cats = {Category::kPerson, Category::kBox, Category::kBall,
                                      Category::kFurniture, Category::kPerson};
  int trials = 0, missed = 0;
  for (int frame = 0; frame < 4000; ++frame) {
    StereoFrame f = EmptyFrame(40, 30);
    for (int i = 0; i < 5; ++i) AddRect(&f, 10 + i, cats[i], cv::Rect(2 + 7 * i, 2, 5, 5));
    AddRect(&f, 9, Category::kRobot, cv::Rect(0, 20, 40, 10));
    model.Apply(&f);
    EXPECT_EQ(CountId(f, 9), 400);  // the robot is never dropped
    EXPECT_TRUE(Listed(f, 9));
    EXPECT_TRUE(Listed(f, 0));
    for (int i = 0; i < 5; ++i) {
      const uint16_t id = 10 + i;
      ++trials;
      const int pixels = CountId(f, id);
      if (pixels == 0) {
        ++missed;
        EXPECT_FALSE(Listed(f, id));
      } else {
        EXPECT_EQ(pixels, 25);
        EXPECT_TRUE(Listed(f, id));
      }
    }
    // Dropped pixels become background, nothing else appears.
    EXPECT_EQ(cv::countNonZero(f.left_instance_id), 400 + 25 * static_cast<int>(f.instances.size() - 2));
  }
  const double rate = static_cast<double>(missed) / trials;
  std::printf("miss rate %.4f over %d instance-frames (configured %.2f)\n", rate, trials, miss_rate);
  EXPECT_NEAR(rate, miss_rate, 0.0085);
}

TEST(SegmentationModel, MissRateOneDropsEveryDetectableInstance) {
  SegmentationModel model(Config(1.0, 2, 0), 1);
  StereoFrame f = EmptyFrame(40, 30);
  AddRect(&f, 3, Category::kBox, cv::Rect(5, 5, 5, 5));
  AddRect(&f, 4, Category::kRobot, cv::Rect(20, 20, 5, 5));
  model.Apply(&f);
  EXPECT_EQ(CountId(f, 3), 0);
  EXPECT_EQ(CountId(f, 4), 25);  // not dilated either
  ASSERT_EQ(f.instances.size(), 2u);
  EXPECT_FALSE(Listed(f, 3));
}

// A 10x10 square dilated by r becomes a (10 + 2r) square at the same centre, exactly.
TEST(SegmentationModel, DilationGrowsSquareByExactlyDilatePxOnEachSide) {
  for (const int r : {1, 2, 3, 7}) {
    SegmentationModel model(Config(0.0, r, 0), 2);
    StereoFrame f = EmptyFrame(100, 80);
    AddRect(&f, 5, Category::kPerson, cv::Rect(40, 30, 10, 10));
    model.Apply(&f);
    const cv::Rect grown(40 - r, 30 - r, 10 + 2 * r, 10 + 2 * r);
    EXPECT_EQ(cv::boundingRect(f.left_instance_id == 5), grown) << "r " << r;
    EXPECT_EQ(CountId(f, 5), grown.area()) << "r " << r;
  }
}

TEST(SegmentationModel, DilationStopsAtImageBorder) {
  SegmentationModel model(Config(0.0, 3, 0), 2);
  StereoFrame f = EmptyFrame(50, 40);
  AddRect(&f, 5, Category::kBall, cv::Rect(0, 0, 4, 4));
  model.Apply(&f);
  EXPECT_EQ(cv::boundingRect(f.left_instance_id == 5), cv::Rect(0, 0, 7, 7));
}

// Two squares 4 px apart (columns 30..33 empty), dilated by 3: A reaches 30..32, B 31..33; the
// contested columns 31 and 32 go to the nearer instance, or without depth to the lower id.
// Neither instance's own pixels, nor the robot's, are ever taken.
StereoFrame TwoSquares() {
  StereoFrame f = EmptyFrame(80, 40);
  AddRect(&f, 7, Category::kBox, cv::Rect(20, 10, 10, 10));     // A: columns 20..29
  AddRect(&f, 12, Category::kPerson, cv::Rect(34, 10, 10, 10));  // B: columns 34..43
  AddRect(&f, 3, Category::kRobot, cv::Rect(20, 22, 24, 5));     // robot just below A and B
  return f;
}

TEST(SegmentationModel, OverlappingDilationLowerIdWinsWithoutDepth) {
  SegmentationModel model(Config(0.0, 3, 0), 2);
  StereoFrame f = TwoSquares();
  model.Apply(&f);
  const int y = 15;
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, 29), 7);
  for (int x = 30; x <= 32; ++x) EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, x), 7) << x;
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, 33), 12);
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, 34), 12);
  EXPECT_EQ(CountId(f, 3), 24 * 5);  // robot pixels kept
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(27, 25), 0);  // below the robot: out of reach of A
}

TEST(SegmentationModel, OverlappingDilationNearerWinsWithDepth) {
  SegmentationModel model(Config(0.0, 3, 0), 2);
  StereoFrame f = TwoSquares();
  f.left_depth_m = cv::Mat(f.left_instance_id.size(), CV_32FC1, cv::Scalar(5.0f));  // wall at 5 m
  f.left_depth_m.setTo(2.0f, f.left_instance_id == 7);   // A at 2 m
  f.left_depth_m.setTo(1.0f, f.left_instance_id == 12);  // B at 1 m: nearer
  f.left_depth_m.setTo(0.1f, f.left_instance_id == 3);
  model.Apply(&f);
  const int y = 15;
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, 29), 7);  // A's own pixels stay A
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, 30), 7);
  for (int x = 31; x <= 34; ++x) EXPECT_EQ(f.left_instance_id.at<uint16_t>(y, x), 12) << x;
  EXPECT_EQ(CountId(f, 3), 24 * 5);
}

// Latency N: the frame k gets the detection of frame k - N, and an empty mask for k < N.
TEST(SegmentationModel, LatencyShiftsMasksByNFrames) {
  const int latency = 2;
  SegmentationModel model(Config(0.0, 1, latency), 2);
  SegmentationModel immediate(Config(0.0, 1, 0), 2);
  std::vector<StereoFrame> expected;
  for (int k = 0; k < 8; ++k) {
    StereoFrame f = EmptyFrame(100, 20);
    AddRect(&f, static_cast<uint16_t>(20 + k), Category::kBox, cv::Rect(5 + 10 * k, 5, 4, 4));
    f.t_ns = k * 50'000'000;
    StereoFrame g = f;
    g.left_instance_id = f.left_instance_id.clone();
    immediate.Apply(&g);
    expected.push_back(g);
    model.Apply(&f);
    EXPECT_EQ(f.t_ns, k * 50'000'000);  // the frame keeps its own time and images
    if (k < latency) {
      EXPECT_EQ(cv::countNonZero(f.left_instance_id), 0) << k;
      ASSERT_EQ(f.instances.size(), 1u);
      EXPECT_EQ(f.instances[0].id, 0);
    } else {
      const StereoFrame& e = expected[k - latency];
      EXPECT_EQ(cv::countNonZero(f.left_instance_id != e.left_instance_id), 0) << k;
      EXPECT_EQ(CountId(f, static_cast<uint16_t>(20 + k - latency)), 36) << k;  // 4x4 dilated by 1
      ASSERT_EQ(f.instances.size(), e.instances.size());
      for (size_t i = 0; i < f.instances.size(); ++i) EXPECT_EQ(f.instances[i].id, e.instances[i].id);
    }
  }
}

std::vector<int> DropPattern(uint64_t seed) {
  SegmentationModel model(Config(0.5, 2, 1), seed);
  std::vector<int> pattern;
  for (int k = 0; k < 200; ++k) {
    StereoFrame f = EmptyFrame(40, 20);
    AddRect(&f, 1, Category::kPerson, cv::Rect(2, 2, 5, 5));
    AddRect(&f, 2, Category::kBox, cv::Rect(20, 2, 5, 5));
    model.Apply(&f);
    pattern.push_back(CountId(f, 1) > 0 ? 1 : 0);
    pattern.push_back(CountId(f, 2) > 0 ? 1 : 0);
  }
  return pattern;
}

TEST(SegmentationModel, SameSeedIdenticalDifferentSeedDiffers) {
  EXPECT_EQ(DropPattern(9), DropPattern(9));
  EXPECT_NE(DropPattern(9), DropPattern(10));
}

TEST(SegmentationModel, FramesWithoutSegmentationAreLeftAlone) {
  SegmentationModel model(Config(0.5, 2, 3), 1);
  StereoFrame f;
  f.instances.push_back(Instance(4, Category::kBox));
  model.Apply(&f);
  EXPECT_TRUE(f.left_instance_id.empty());
  EXPECT_EQ(f.instances.size(), 1u);
}

TEST(SegmentationModel, RejectsBadInput) {
  EXPECT_THROW(SegmentationModel(Config(-0.1, 2, 0), 1), InputError);
  EXPECT_THROW(SegmentationModel(Config(1.5, 2, 0), 1), InputError);
  EXPECT_THROW(SegmentationModel(Config(0.1, -1, 0), 1), InputError);
  EXPECT_THROW(SegmentationModel(Config(0.1, 2, -1), 1), InputError);
  SegmentationModel model(Config(0.1, 2, 0), 1);
  EXPECT_THROW(model.Apply(nullptr), InputError);
  StereoFrame f;
  f.left_instance_id = cv::Mat::zeros(10, 10, CV_8UC1);
  EXPECT_THROW(model.Apply(&f), InputError);
}

}  // namespace
}  // namespace viqu::sim

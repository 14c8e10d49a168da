// Tests of sim::SegmentationModel: misses, minimum area, wrong categories, dilation, boundary
// jitter, spurious masks, latency, determinism, independence of the steps' draws, validation.
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"
#include "sim/segmentation_model.h"

namespace viqu::sim {
namespace {

// Misses, dilation and latency only: the newer steps (minimum area, wrong category, boundary
// jitter, spurious masks) switched off, whatever their defaults.
SegmentationConfig Config(double miss_rate, int dilate_px, int latency_frames) {
  SegmentationConfig c;
  c.miss_rate = miss_rate;
  c.dilate_px = dilate_px;
  c.latency_frames = latency_frames;
  c.min_area_px = 0;
  c.false_positive_rate = 0;
  c.wrong_category_rate = 0;
  c.boundary_jitter_px = 0;
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


// ---------------------------------------------------------------------------------------------
// The newer steps: minimum area, wrong category, boundary jitter, spurious masks.

bool Movable(Category c) { return c == Category::kPerson || c == Category::kBox || c == Category::kBall; }

bool Confusable(Category c) { return Movable(c) || c == Category::kFurniture; }

// 9 x 11 = 99 px vanishes at min_area_px 100 and 10 x 10 = 100 px stays; the area is that of the
// visible pixels of the ideal image (a 12 x 10 ball with 3 of its columns behind the robot has
// 90), counted before dilation; the robot (30 px) is never subject to it; a listed instance
// without pixels has area 0.
TEST(SegmentationModel, MinAreaDropsInstancesWithFewerVisiblePixels) {
  for (const int dilate : {0, 2}) {
    SegmentationConfig c = Config(0.0, dilate, 0);
    c.min_area_px = 100;
    SegmentationModel model(c, 3);
    StereoFrame f = EmptyFrame(100, 60);
    AddRect(&f, 5, Category::kPerson, cv::Rect(5, 5, 9, 11));   // 99 px
    AddRect(&f, 6, Category::kBox, cv::Rect(30, 5, 10, 10));    // 100 px
    AddRect(&f, 7, Category::kBall, cv::Rect(60, 5, 12, 10));   // 120 px, 30 of them covered next
    AddRect(&f, 8, Category::kRobot, cv::Rect(60, 5, 3, 10));   // 30 px in front of the ball
    f.instances.push_back(Instance(9, Category::kFurniture));   // listed, no pixels
    model.Apply(&f);
    EXPECT_EQ(CountId(f, 5), 0) << dilate;
    EXPECT_FALSE(Listed(f, 5)) << dilate;
    EXPECT_EQ(CountId(f, 6), (10 + 2 * dilate) * (10 + 2 * dilate)) << dilate;
    EXPECT_TRUE(Listed(f, 6)) << dilate;
    EXPECT_EQ(CountId(f, 7), 0) << dilate;
    EXPECT_FALSE(Listed(f, 7)) << dilate;
    EXPECT_EQ(CountId(f, 8), 30) << dilate;
    EXPECT_TRUE(Listed(f, 8)) << dilate;
    EXPECT_FALSE(Listed(f, 9)) << dilate;
    EXPECT_TRUE(Listed(f, 0)) << dilate;
  }
  // Switched off (0), the listed instance without pixels stays listed, as before.
  SegmentationModel off(Config(0.0, 0, 0), 3);
  StereoFrame f = EmptyFrame(20, 20);
  AddRect(&f, 5, Category::kPerson, cv::Rect(1, 1, 2, 2));
  f.instances.push_back(Instance(9, Category::kFurniture));
  off.Apply(&f);
  EXPECT_EQ(CountId(f, 5), 4);
  EXPECT_TRUE(Listed(f, 9));
}

// Four instances, rate 0.3, 4000 frames = 16000 trials: std sqrt(0.3 * 0.7 / 16000) = 0.0036,
// bound 4 std = 0.0145. Each original category goes to each of the three others with share 1/3;
// about 1200 relabels per category give a share std of sqrt(2/9 / 1200) = 0.0136, bound 0.07.
TEST(SegmentationModel, WrongCategoryRateRelabelsToAnotherConfusableCategoryAtTheRate) {
  const double rate = 0.3;
  SegmentationConfig c = Config(0.0, 0, 0);
  c.wrong_category_rate = rate;
  SegmentationModel model(c, 21);
  const std::vector<Category> cats = {Category::kPerson, Category::kBox, Category::kBall,
                                      Category::kFurniture};
  std::map<std::pair<Category, Category>, int> confusion;  // (true, reported) -> count
  int trials = 0, relabelled = 0;
  for (int frame = 0; frame < 4000; ++frame) {
    StereoFrame f = EmptyFrame(50, 20);
    for (int i = 0; i < 4; ++i) AddRect(&f, 10 + i, cats[i], cv::Rect(2 + 10 * i, 2, 6, 6));
    AddRect(&f, 2, Category::kRobot, cv::Rect(0, 12, 50, 8));
    const cv::Mat ideal = f.left_instance_id.clone();
    const std::vector<SegmentInstance> listed = f.instances;
    model.Apply(&f);
    // Only categories change: same pixels, same ids and names in the same order.
    ASSERT_EQ(cv::countNonZero(f.left_instance_id != ideal), 0);
    ASSERT_EQ(f.instances.size(), listed.size());
    for (size_t i = 0; i < listed.size(); ++i) {
      const SegmentInstance& in = listed[i];
      const SegmentInstance& out = f.instances[i];
      EXPECT_EQ(out.id, in.id);
      EXPECT_EQ(out.name, in.name);
      if (!Confusable(in.category)) {
        EXPECT_EQ(out.category, in.category);  // background and robot are never relabelled
        continue;
      }
      EXPECT_TRUE(Confusable(out.category)) << CategoryName(out.category);
      ++trials;
      if (out.category != in.category) ++relabelled;
      ++confusion[{in.category, out.category}];
    }
  }
  const double observed = static_cast<double>(relabelled) / trials;
  std::printf("wrong category rate %.4f over %d instance-frames (configured %.2f)\n", observed, trials, rate);
  EXPECT_NEAR(observed, rate, 0.0145);
  for (const Category truth : cats) {
    int changed = 0;
    for (const Category reported : cats) {
      if (reported != truth) changed += confusion[{truth, reported}];
    }
    for (const Category reported : cats) {
      if (reported == truth) continue;
      EXPECT_NEAR(static_cast<double>(confusion[{truth, reported}]) / changed, 1.0 / 3.0, 0.07)
          << CategoryName(truth) << " -> " << CategoryName(reported);
    }
  }
}

// A 20 x 20 square: every frame it is exactly the square grown by r = dilate_px + d on every side,
// d uniform in [-jitter, +jitter]. 600 frames, 2j+1 values of probability p each: share std
// sqrt(p (1 - p) / 600), bound 4.5 std.
TEST(SegmentationModel, BoundaryJitterMovesEverySideByOneDrawnAmountWithinJitter) {
  const std::vector<std::pair<int, int>> cases = {{0, 2}, {2, 1}, {0, 1}};  // (dilate_px, jitter)
  for (const auto& [dilate, jitter] : cases) {
    SegmentationConfig c = Config(0.0, dilate, 0);
    c.boundary_jitter_px = jitter;
    SegmentationModel model(c, 8);
    std::map<int, int> seen;  // r -> frames
    const int frames = 600;
    for (int k = 0; k < frames; ++k) {
      StereoFrame f = EmptyFrame(80, 60);
      AddRect(&f, 5, Category::kPerson, cv::Rect(30, 20, 20, 20));
      model.Apply(&f);
      const cv::Rect box = cv::boundingRect(f.left_instance_id == 5);
      const int r = (box.width - 20) / 2;
      ASSERT_GE(r, dilate - jitter);
      ASSERT_LE(r, dilate + jitter);
      ASSERT_EQ(box, cv::Rect(30 - r, 20 - r, 20 + 2 * r, 20 + 2 * r));
      ASSERT_EQ(CountId(f, 5), box.area());  // a full square
      ++seen[r];
    }
    const double p = 1.0 / (2 * jitter + 1);
    const double bound = 4.5 * std::sqrt(p * (1 - p) / frames);
    for (int r = dilate - jitter; r <= dilate + jitter; ++r) {
      EXPECT_NEAR(static_cast<double>(seen[r]) / frames, p, bound) << "dilate " << dilate << " r " << r;
    }
  }
}

// Any shape: the mask lies between the original eroded and dilated by jitter px (a square
// (2j+1) element), and is exactly the original eroded or dilated by one d in [-j, j].
TEST(SegmentationModel, BoundaryJitterKeepsAnyShapeWithinJitterOfItsBoundary) {
  const int jitter = 2;
  SegmentationConfig c = Config(0.0, 0, 0);
  c.boundary_jitter_px = jitter;
  SegmentationModel model(c, 4);
  StereoFrame ideal = EmptyFrame(80, 60);
  cv::circle(ideal.left_instance_id, cv::Point(40, 30), 10, cv::Scalar(6), cv::FILLED);
  cv::fillConvexPoly(ideal.left_instance_id, std::vector<cv::Point>{{5, 5}, {25, 8}, {12, 25}}, cv::Scalar(6));
  ideal.instances.push_back(Instance(6, Category::kBall));
  const cv::Mat own = ideal.left_instance_id == 6;
  std::map<int, cv::Mat> morphed;  // d -> own eroded (d < 0) or dilated (d > 0) by |d|
  for (int d = -jitter; d <= jitter; ++d) {
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * std::abs(d) + 1, 2 * std::abs(d) + 1));
    if (d < 0) cv::erode(own, morphed[d], kernel);
    else cv::dilate(own, morphed[d], kernel);
  }
  std::set<int> seen;
  for (int k = 0; k < 200; ++k) {
    StereoFrame f = ideal;
    f.left_instance_id = ideal.left_instance_id.clone();
    model.Apply(&f);
    const cv::Mat mask = f.left_instance_id == 6;
    ASSERT_EQ(cv::countNonZero(morphed[-jitter] & ~mask), 0) << "shrank by more than jitter";
    ASSERT_EQ(cv::countNonZero(mask & ~morphed[jitter]), 0) << "grew by more than jitter";
    int match = 99;
    for (int d = -jitter; d <= jitter; ++d) {
      if (cv::countNonZero(mask != morphed[d]) == 0) match = d;
    }
    ASSERT_NE(match, 99) << "frame " << k << " is not one erosion or dilation of the original";
    seen.insert(match);
  }
  EXPECT_EQ(seen.size(), static_cast<size_t>(2 * jitter + 1));
}

// Shrinking by 1: a 10 x 10 square in the image corner keeps its sides on the image border
// (the object continues beyond it) and becomes 9 x 9; a 2 x 2 square vanishes and leaves the list.
TEST(SegmentationModel, BoundaryJitterDoesNotErodeAtTheImageBorderAndDropsVanishedInstances) {
  SegmentationConfig c = Config(0.0, 0, 0);
  c.boundary_jitter_px = 1;
  SegmentationModel model(c, 5);
  std::set<int> corner_areas, small_areas;
  for (int k = 0; k < 300; ++k) {
    StereoFrame f = EmptyFrame(60, 40);
    AddRect(&f, 3, Category::kBox, cv::Rect(0, 0, 10, 10));
    AddRect(&f, 4, Category::kBall, cv::Rect(40, 20, 2, 2));
    model.Apply(&f);
    const int corner = CountId(f, 3);
    ASSERT_TRUE(corner == 81 || corner == 100 || corner == 121) << corner;
    const int side = corner == 81 ? 9 : corner == 100 ? 10 : 11;
    ASSERT_EQ(cv::boundingRect(f.left_instance_id == 3), cv::Rect(0, 0, side, side));
    corner_areas.insert(corner);
    const int small = CountId(f, 4);
    ASSERT_TRUE(small == 0 || small == 4 || small == 16) << small;
    ASSERT_EQ(Listed(f, 4), small > 0);
    small_areas.insert(small);
  }
  EXPECT_EQ(corner_areas, (std::set<int>{81, 100, 121}));
  EXPECT_EQ(small_areas, (std::set<int>{0, 4, 16}));
}

// Rate 0.2 over 3000 frames: std sqrt(0.2 * 0.8 / 3000) = 0.0073, bound 4 std = 0.03. About 600
// spurious masks: category share std sqrt(2/9 / 600) = 0.019, bound 0.08.
TEST(SegmentationModel, SpuriousMasksAppearAtTheRateOnBackgroundPixelsWithFreshIds) {
  const double rate = 0.2;
  SegmentationConfig c = Config(0.0, 0, 0);
  c.false_positive_rate = rate;
  SegmentationModel model(c, 31);
  std::set<uint16_t> ids;
  std::map<Category, int> categories;
  int spurious = 0;
  const int frames = 3000;
  for (int k = 0; k < frames; ++k) {
    StereoFrame f = EmptyFrame(80, 60);
    AddRect(&f, 3, Category::kPerson, cv::Rect(10, 10, 20, 20));  // 400 px
    AddRect(&f, 1, Category::kRobot, cv::Rect(0, 50, 80, 10));     // 800 px
    const cv::Mat ideal = f.left_instance_id.clone();
    model.Apply(&f);
    ASSERT_EQ(CountId(f, 3), 400);
    ASSERT_EQ(CountId(f, 1), 800);
    std::vector<SegmentInstance> extra;
    for (const auto& s : f.instances) {
      if (s.id != 0 && s.id != 1 && s.id != 3) extra.push_back(s);
    }
    ASSERT_LE(extra.size(), 1u);
    if (extra.empty()) {
      ASSERT_EQ(cv::countNonZero(f.left_instance_id != ideal), 0);
      continue;
    }
    const SegmentInstance& s = extra[0];
    ++spurious;
    EXPECT_EQ(s.id, 65535 - (spurious - 1));  // counting down from 65535, no wrap here
    EXPECT_TRUE(ids.insert(s.id).second) << "id " << s.id << " reused";
    EXPECT_EQ(s.name, "spurious_" + std::to_string(spurious));
    EXPECT_TRUE(Movable(s.category)) << CategoryName(s.category);
    ++categories[s.category];
    const cv::Mat blob = f.left_instance_id == s.id;
    EXPECT_GT(cv::countNonZero(blob), 0);
    EXPECT_EQ(cv::countNonZero(blob & (ideal != 0)), 0) << "spurious pixels on an instance";
    EXPECT_EQ(cv::countNonZero((f.left_instance_id != ideal) & ~blob), 0) << "other pixels changed";
    const cv::Rect box = cv::boundingRect(blob);
    EXPECT_LE(box.width, 2 * SegmentationModel::kSpuriousMaxSemiAxisPx + 1);
    EXPECT_LE(box.height, 2 * SegmentationModel::kSpuriousMaxSemiAxisPx + 1);
  }
  const double observed = static_cast<double>(spurious) / frames;
  std::printf("spurious mask rate %.4f over %d frames (configured %.2f)\n", observed, frames, rate);
  EXPECT_NEAR(observed, rate, 0.03);
  for (const Category cat : {Category::kPerson, Category::kBox, Category::kBall}) {
    EXPECT_NEAR(static_cast<double>(categories[cat]) / spurious, 1.0 / 3.0, 0.08) << CategoryName(cat);
  }
}

// On a 300 x 300 background, a blob away from the border is a whole ellipse with semi-axes in
// [8, 40] px: its bounding box spans at least 2 * 8 - 1 and at most 2 * 40 + 1 px either way, its
// area lies between about pi 8^2 = 201 and pi 40^2 = 5027 px (10% margin for rasterisation).
TEST(SegmentationModel, SpuriousBlobSizesStayInTheDocumentedRange) {
  SegmentationConfig c = Config(0.0, 0, 0);
  c.false_positive_rate = 1.0;
  SegmentationModel model(c, 12);
  const int lo = SegmentationModel::kSpuriousMinSemiAxisPx, hi = SegmentationModel::kSpuriousMaxSemiAxisPx;
  int whole = 0, min_side = 1000, max_side = 0;
  for (int k = 0; k < 300; ++k) {
    StereoFrame f = EmptyFrame(300, 300);
    model.Apply(&f);
    ASSERT_EQ(f.instances.size(), 2u);  // rate 1: one every frame
    const cv::Mat blob = f.left_instance_id == f.instances[1].id;
    const cv::Rect box = cv::boundingRect(blob);
    if (box.x == 0 || box.y == 0 || box.br().x == 300 || box.br().y == 300) continue;  // clipped
    ++whole;
    const int area = cv::countNonZero(blob);
    EXPECT_GE(std::min(box.width, box.height), 2 * lo - 1);
    EXPECT_LE(std::max(box.width, box.height), 2 * hi + 1);
    EXPECT_GE(area, 0.9 * M_PI * lo * lo);
    EXPECT_LE(area, 1.1 * M_PI * hi * hi);
    min_side = std::min(min_side, std::min(box.width, box.height));
    max_side = std::max(max_side, std::max(box.width, box.height));
  }
  EXPECT_GT(whole, 200);
  EXPECT_LT(min_side, 25);  // both ends of the range occur
  EXPECT_GT(max_side, 70);
}

// Ids stay above every input id seen so far: with 65533 in the input only 65535 and 65534 are
// left, used in turn (wrapping); with 65535 in the input no id is left; without a background
// pixel there is nowhere to put a blob.
TEST(SegmentationModel, SpuriousIdsStayAboveInputIdsAndWrap) {
  SegmentationConfig c = Config(0.0, 0, 0);
  c.false_positive_rate = 1.0;
  SegmentationModel model(c, 2);
  const std::vector<uint16_t> expected = {65535, 65534, 65535, 65534, 65535};
  for (size_t k = 0; k < expected.size(); ++k) {
    StereoFrame f = EmptyFrame(100, 100);
    AddRect(&f, 65533, Category::kBox, cv::Rect(0, 0, 20, 20));
    model.Apply(&f);
    ASSERT_EQ(f.instances.size(), 3u);
    EXPECT_EQ(f.instances[2].id, expected[k]) << k;
    EXPECT_EQ(f.instances[2].name, "spurious_" + std::to_string(k + 1));
    EXPECT_EQ(CountId(f, 65533), 400);
  }
  StereoFrame top = EmptyFrame(100, 100);
  top.instances.push_back(Instance(65535, Category::kBall));  // listed only: still taken
  model.Apply(&top);
  EXPECT_EQ(top.instances.size(), 2u);
  EXPECT_EQ(cv::countNonZero(top.left_instance_id), 0);

  SegmentationModel full(c, 2);
  StereoFrame f = EmptyFrame(30, 30);
  AddRect(&f, 1, Category::kRobot, cv::Rect(0, 0, 30, 30));
  full.Apply(&f);
  EXPECT_EQ(f.instances.size(), 2u);
  EXPECT_EQ(CountId(f, 1), 900);
}

// A fixed sequence of frames: background, a robot band, four detectable instances of random
// size, position and depth (later ones paint over earlier ones), and a listed instance without
// pixels. Integer arithmetic on a seeded engine only, so the frames are the same everywhere.
StereoFrame GoldenFrame(std::mt19937_64* g) {
  StereoFrame f;
  f.left_instance_id = cv::Mat::zeros(60, 100, CV_16UC1);
  f.left_depth_m = cv::Mat(60, 100, CV_32FC1, cv::Scalar(5.0f));
  f.instances.push_back(SegmentInstance{0, Category::kBackground, "background"});
  const Category cats[4] = {Category::kPerson, Category::kBox, Category::kBall, Category::kFurniture};
  for (int i = 0; i < 4; ++i) {
    const int w = 3 + static_cast<int>((*g)() % 25), h = 3 + static_cast<int>((*g)() % 25);
    const int x = static_cast<int>((*g)() % (100 - w)), y = static_cast<int>((*g)() % (52 - h));
    const float depth_m = 0.5f + 0.25f * static_cast<float>((*g)() % 12);
    const cv::Rect r(x, y, w, h);
    f.left_instance_id(r).setTo(2 + i);
    f.left_depth_m(r).setTo(depth_m);
    f.instances.push_back(SegmentInstance{static_cast<uint16_t>(2 + i), cats[i], "obj" + std::to_string(i)});
  }
  f.left_instance_id(cv::Rect(0, 52, 100, 8)).setTo(1);
  f.instances.push_back(SegmentInstance{1, Category::kRobot, "trunk"});
  f.instances.push_back(SegmentInstance{6, Category::kBox, "hidden"});
  return f;
}

// FNV-1a over every output image and instance list of `frames` frames through `model`.
uint64_t OutputChecksum(SegmentationModel* model, int frames) {
  std::mt19937_64 g(1234);
  uint64_t h = 0xcbf29ce484222325ULL;
  auto mix = [&h](const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
  };
  for (int k = 0; k < frames; ++k) {
    StereoFrame f = GoldenFrame(&g);
    model->Apply(&f);
    for (int y = 0; y < f.left_instance_id.rows; ++y) {
      mix(f.left_instance_id.ptr(y), f.left_instance_id.cols * sizeof(uint16_t));
    }
    for (const auto& s : f.instances) {
      mix(&s.id, sizeof(s.id));
      mix(&s.category, sizeof(s.category));
      mix(s.name.data(), s.name.size());
    }
  }
  return h;
}

SegmentationConfig AllOn() {
  SegmentationConfig c;
  c.miss_rate = 0.2;
  c.dilate_px = 2;
  c.latency_frames = 1;
  c.min_area_px = 30;
  c.false_positive_rate = 0.3;
  c.wrong_category_rate = 0.2;
  c.boundary_jitter_px = 1;
  return c;
}

TEST(SegmentationModel, AllStepsSameSeedIdenticalDifferentSeedDiffers) {
  SegmentationModel a(AllOn(), 5), b(AllOn(), 5), other(AllOn(), 6);
  const uint64_t sum = OutputChecksum(&a, 200);
  EXPECT_EQ(sum, OutputChecksum(&b, 200));
  EXPECT_NE(sum, OutputChecksum(&other, 200));
}

// With the newer steps off, the output is bit for bit that of the implementation before them
// (checksums computed with sim/segmentation_model.cc of commit b09284b on the same frames).
TEST(SegmentationModel, NewStepsSwitchedOffReproduceTheEarlierOutput) {
  SegmentationModel a(Config(0.3, 2, 1), 42), b(Config(0.1, 3, 0), 7);
  EXPECT_EQ(OutputChecksum(&a, 300), 0xa945be8ee65b4c78ULL);
  EXPECT_EQ(OutputChecksum(&b, 300), 0x5d855598566d7437ULL);
}

// Per frame of the golden sequence: which real ids (2..6) are listed, their categories, the
// pixels of real ids (spurious ones read as 0), and the spurious entries.
struct Outcome {
  std::vector<std::set<uint16_t>> listed;
  std::vector<std::map<uint16_t, Category>> categories;
  std::vector<cv::Mat> real_pixels;
  std::vector<std::vector<std::string>> spurious;  // "name category"
};

Outcome RunGolden(const SegmentationConfig& c, uint64_t seed) {
  SegmentationModel model(c, seed);
  std::mt19937_64 g(99);
  Outcome o;
  for (int k = 0; k < 300; ++k) {
    StereoFrame f = GoldenFrame(&g);
    model.Apply(&f);
    o.listed.emplace_back();
    o.categories.emplace_back();
    o.spurious.emplace_back();
    cv::Mat real = f.left_instance_id.clone();
    for (const auto& s : f.instances) {
      if (s.id <= 6) {
        o.listed.back().insert(s.id);
        o.categories.back()[s.id] = s.category;
      } else {
        o.spurious.back().push_back(s.name + " " + CategoryName(s.category));
        real.setTo(0, real == s.id);
      }
    }
    o.real_pixels.push_back(real);
  }
  return o;
}

bool SamePixels(const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (cv::countNonZero(a[i] != b[i]) != 0) return false;
  }
  return true;
}

// Each step draws from its own stream, a fixed number of draws per frame: turning the other
// steps on or up does not change its outcomes.
TEST(SegmentationModel, EachStepsDrawsDoNotDependOnTheOtherSettings) {
  SegmentationConfig misses = Config(0.3, 0, 0);
  SegmentationConfig misses_plus = misses;
  misses_plus.wrong_category_rate = 0.5;
  misses_plus.false_positive_rate = 0.5;
  misses_plus.boundary_jitter_px = 2;
  misses_plus.dilate_px = 2;  // with jitter 2 masks never shrink, so none vanishes
  const Outcome m0 = RunGolden(misses, 3), m1 = RunGolden(misses_plus, 3);
  EXPECT_EQ(m0.listed, m1.listed);
  EXPECT_NE(m0.listed, RunGolden(misses, 4).listed);  // the comparison can tell

  SegmentationConfig wrong = Config(0.0, 0, 0);
  wrong.wrong_category_rate = 0.3;
  SegmentationConfig wrong_plus = wrong;
  wrong_plus.miss_rate = 0.5;
  wrong_plus.false_positive_rate = 0.5;
  wrong_plus.boundary_jitter_px = 2;
  const Outcome w0 = RunGolden(wrong, 3), w1 = RunGolden(wrong_plus, 3);
  int compared = 0;
  for (size_t k = 0; k < w0.categories.size(); ++k) {
    for (const auto& [id, cat] : w1.categories[k]) {
      if (id == 0 || id == 1) continue;
      ASSERT_EQ(w0.categories[k].count(id), 1u);
      EXPECT_EQ(w0.categories[k].at(id), cat) << "frame " << k << " id " << id;
      ++compared;
    }
  }
  EXPECT_GT(compared, 300);

  SegmentationConfig jitter = Config(0.0, 1, 0);
  jitter.boundary_jitter_px = 2;
  SegmentationConfig jitter_plus = jitter;
  jitter_plus.wrong_category_rate = 0.5;
  jitter_plus.false_positive_rate = 0.5;
  const Outcome jit0 = RunGolden(jitter, 3), jit1 = RunGolden(jitter_plus, 3);
  EXPECT_TRUE(SamePixels(jit0.real_pixels, jit1.real_pixels));
  EXPECT_FALSE(SamePixels(jit0.real_pixels, RunGolden(jitter, 4).real_pixels));

  SegmentationConfig spurious = Config(0.0, 0, 0);
  spurious.false_positive_rate = 0.3;
  SegmentationConfig spurious_plus = spurious;
  spurious_plus.miss_rate = 0.3;
  spurious_plus.wrong_category_rate = 0.5;
  spurious_plus.boundary_jitter_px = 1;
  const Outcome s0 = RunGolden(spurious, 3), s1 = RunGolden(spurious_plus, 3);
  EXPECT_EQ(s0.spurious, s1.spurious);
  EXPECT_NE(s0.spurious, RunGolden(spurious, 4).spurious);
}

TEST(SegmentationModel, RejectsOutOfRangeNewSettings) {
  SegmentationConfig c = Config(0.0, 0, 0);
  const auto rejected = [](const SegmentationConfig& bad) {
    try {
      SegmentationModel model(bad, 1);
    } catch (const InputError&) {
      return true;
    }
    return false;
  };
  SegmentationConfig negative_area = c;
  negative_area.min_area_px = -1;
  EXPECT_TRUE(rejected(negative_area));
  SegmentationConfig negative_jitter = c;
  negative_jitter.boundary_jitter_px = -1;
  EXPECT_TRUE(rejected(negative_jitter));
  for (const double v : {-0.1, 1.1, static_cast<double>(NAN)}) {
    SegmentationConfig b = c;
    b.false_positive_rate = v;
    EXPECT_TRUE(rejected(b)) << "false_positive_rate " << v;
    b = c;
    b.wrong_category_rate = v;
    EXPECT_TRUE(rejected(b)) << "wrong_category_rate " << v;
  }
  c.false_positive_rate = 1.0;
  c.wrong_category_rate = 1.0;
  c.min_area_px = 100000;
  c.boundary_jitter_px = 50;
  EXPECT_FALSE(rejected(c));
}

}  // namespace
}  // namespace viqu::sim

// Freeing culled map objects (slam/core/map.h, Map::Reclaim): what is freed, what stays, and
// that nothing left behind points at freed memory (run under ASan by scripts/sanitize.sh).
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/map.h"

namespace viqu::slam {
namespace {

constexpr int kFeatures = 10;

Frame MakeFrame(int64_t t_ns) {
  auto f = std::make_shared<FrameFeatures>();
  f->keypoints.assign(kFeatures, FeaturePoint(cv::Point2f(10.f, 10.f), 0));
  f->descriptors = cv::Mat::zeros(kFeatures, 32, CV_8U);
  for (int r = 0; r < kFeatures; ++r) f->descriptors.row(r).setTo(r + 1);  // a different one per feature
  f->u_right.assign(kFeatures, -1.f);
  f->depth.assign(kFeatures, -1.f);
  f->object.assign(kFeatures, 0);
  f->level_scale = {1.f};
  f->level_sigma2 = {1.f};
  Frame frame;
  frame.t_ns = t_ns;
  frame.Reset(f);
  return frame;
}

TEST(MapReclaim, FreesUnpinnedCulledObjectsAndLeavesNoLinkToThem) {
  Map map;
  std::vector<KeyFrame*> kfs;
  for (int k = 0; k < 3; ++k) kfs.push_back(map.AddKeyFrame(MakeFrame(k)));
  std::vector<MapPoint*> pts;
  for (int i = 0; i < kFeatures; ++i) {
    pts.push_back(map.AddPoint(Eigen::Vector3d(i, 0, 2), kfs[1]));  // all made by the middle keyframe
    for (KeyFrame* kf : kfs) Map::AddObservation(pts[i], kf, i);
  }
  for (KeyFrame* kf : kfs) kf->UpdateConnections(1);
  ASSERT_EQ(kfs[0]->covisible.count(kfs[1]), 1u);

  map.EraseKeyFrame(kfs[1], 1);  // culled: its points keep two observations each
  Map::ErasePoint(pts[2]);
  Map::ErasePoint(pts[3]);
  Map::Replace(pts[4], pts[5]);  // duplicate fusion: 4 goes bad
  const int good_points = map.GoodPoints();
  EXPECT_EQ(good_points, kFeatures - 3);

  // Point 3 is still held by someone (a frame): it stays, flagged bad.
  const std::vector<const KeyFrame*> no_kfs;
  const std::vector<const MapPoint*> pin3 = {pts[3]};
  EXPECT_EQ(map.Reclaim(no_kfs, pin3), 3u);  // keyframe 1, points 2 and 4
  EXPECT_EQ(map.keyframes_freed(), 1);
  EXPECT_EQ(map.points_freed(), 2);
  ASSERT_EQ(map.keyframes().size(), 2u);
  EXPECT_EQ(map.keyframes()[0]->id, 0);  // order kept
  EXPECT_EQ(map.keyframes()[1]->id, 2);
  EXPECT_EQ(map.points().size(), static_cast<size_t>(kFeatures - 2));
  EXPECT_EQ(map.GoodPoints(), good_points);
  EXPECT_TRUE(pts[3]->bad);
  // No link to the freed keyframe: references forgotten, covisibility and observations clean.
  for (const auto& p : map.points()) {
    EXPECT_EQ(p->reference, nullptr) << p->id;
    for (const auto& [kf, idx] : p->observations) EXPECT_TRUE(kf == kfs[0] || kf == kfs[2]);
  }
  for (const auto& kf : map.keyframes()) {
    for (const auto& [n, w] : kf->covisible) EXPECT_NE(n, kfs[1]);  // (count() would read the freed id)
    for (MapPoint* p : kf->points) EXPECT_TRUE(p == nullptr || !p->bad);
  }
  // A good point whose reference is gone still summarises its observations.
  pts[0]->UpdateFromObservations();
  const auto& [obs_kf, obs_idx] = *pts[0]->observations.begin();
  EXPECT_EQ(DescriptorDistance(pts[0]->descriptor.data(), obs_kf->features->descriptors.ptr<uint8_t>(obs_idx)), 0);

  // Ids keep counting past the freed objects.
  EXPECT_EQ(map.AddKeyFrame(MakeFrame(9))->id, 3);
  EXPECT_EQ(map.AddPoint(Eigen::Vector3d(0, 0, 1), kfs[0])->id, kFeatures);

  // Unpinned, point 3 goes too; pinned keyframes stay even when bad.
  map.EraseKeyFrame(kfs[2], 1);
  const std::vector<const KeyFrame*> pin_kf2 = {kfs[2]};
  EXPECT_EQ(map.Reclaim(pin_kf2, {}), 1u);  // point 3
  EXPECT_EQ(map.keyframes().size(), 3u);
  EXPECT_TRUE(kfs[2]->bad);
  const int good_before = map.GoodPoints();  // still seen by keyframe 0
  EXPECT_EQ(map.Reclaim({}, {}), 1u);        // keyframe 2
  EXPECT_EQ(map.GoodKeyFrames(), 2);
  EXPECT_EQ(map.GoodPoints(), good_before);
  EXPECT_EQ(map.points().size(), static_cast<size_t>(good_before));
}

}  // namespace
}  // namespace viqu::slam

// Fusion of duplicate map points (slam/core/matcher.h, Matcher::Fuse): a point projected into a
// keyframe whose matching feature already has a map point merges with it, the point with fewer
// observations handing its observations to the other. The merge must agree with those
// observations: on a repetitive texture, a keyframe without stereo depth for a feature sees two
// different points on one ray as the same, and merging them gave a keyframe an observation of a
// point behind its camera (standing_crowd, session 33: local BA's cost went from 2.5e3 to 3.7e6
// and the window's keyframes moved 9-50 mm).
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/map.h"
#include "slam/core/matcher.h"
#include "synthetic_camera.h"
#include "synthetic_keyframes.h"

namespace viqu::slam {
namespace {

using testing::AddKeyFrame;
using testing::AddPoint;

// Keyframe A at the origin sees point Q 1 m ahead (so does C, 0.2 m to its side). A point P made
// by another keyframe lies on A's ray through Q, projects onto Q's feature in A and carries the
// same descriptor: the search in A cannot tell them apart.
struct Scene {
  StereoCamera cam = testing::SyntheticStereoCamera();
  Map map;
  KeyFrame* a = nullptr;
  KeyFrame* c = nullptr;
  MapPoint* q = nullptr;
  Scene() {
    const Eigen::Vector3d q_w(0, 0, 1);
    a = AddKeyFrame(&map, cam, Eigen::Vector3d::Zero(), q_w, 0);
    c = AddKeyFrame(&map, cam, Eigen::Vector3d(0.2, 0, 0), q_w, 0);
    q = AddPoint(&map, q_w, {a, c});
  }
};

TEST(MatcherFuse, DoesNotMergeAPointThatWouldLieBehindTheOtherKeyframe) {
  Scene s;
  // P, 2 m along A's ray, made by keyframe B at (0.3, 0, 1.5), which Q (1 m ahead of A) is behind.
  const Eigen::Vector3d p_w(0, 0, 2);
  KeyFrame* b = AddKeyFrame(&s.map, s.cam, Eigen::Vector3d(0.3, 0, 1.5), p_w, 6);  // 0.58 m away: a coarse level
  MapPoint* p = AddPoint(&s.map, p_w, {b});
  ASSERT_LT((s.a->T_c_w * p_w - Eigen::Vector3d(0, 0, 2)).norm(), 1e-12);
  ASSERT_LT((b->T_c_w * s.q->p_w).z(), 0.0);  // Q is behind B

  const Matcher matcher(s.cam, MatcherOptions());
  EXPECT_EQ(matcher.Fuse(s.a, {p}, 3.0), 0);
  EXPECT_FALSE(p->bad);
  EXPECT_FALSE(s.q->bad);
  EXPECT_EQ(b->points[0], p);
  EXPECT_EQ(s.a->points[0], s.q);
  EXPECT_EQ(s.q->observations.size(), 2u);
  EXPECT_EQ(p->observations.size(), 1u);
}

TEST(MatcherFuse, DoesNotMergeAPointThatProjectsFarFromTheOtherKeyframesFeature) {
  Scene s;
  // P 1.6 m along A's ray, made by keyframe B 0.3 m to the side: Q is in front of B but projects
  // 45 px from the feature that made P.
  const Eigen::Vector3d p_w(0, 0, 1.6);
  KeyFrame* b = AddKeyFrame(&s.map, s.cam, Eigen::Vector3d(0.3, 0, 0), p_w, 0);
  MapPoint* p = AddPoint(&s.map, p_w, {b});
  const Eigen::Vector2d q_in_b = s.cam.Project(b->T_c_w * s.q->p_w);
  ASSERT_GT((q_in_b - Eigen::Vector2d(b->features->keypoints[0].pt.x, b->features->keypoints[0].pt.y)).norm(), 30.0);

  const Matcher matcher(s.cam, MatcherOptions());
  EXPECT_EQ(matcher.Fuse(s.a, {p}, 3.0), 0);
  EXPECT_FALSE(p->bad);
  EXPECT_EQ(b->points[0], p);
}

TEST(MatcherFuse, MergesATrueDuplicate) {
  Scene s;
  // P 1 mm beyond Q on A's ray, made by keyframe B 0.1 m to the side: the same point.
  const Eigen::Vector3d p_w(0, 0, 1.001);
  KeyFrame* b = AddKeyFrame(&s.map, s.cam, Eigen::Vector3d(0.1, 0, 0), p_w, 0);
  MapPoint* p = AddPoint(&s.map, p_w, {b});

  const Matcher matcher(s.cam, MatcherOptions());
  EXPECT_EQ(matcher.Fuse(s.a, {p}, 3.0), 1);
  EXPECT_TRUE(p->bad);  // the one with fewer observations goes
  EXPECT_FALSE(s.q->bad);
  EXPECT_EQ(b->points[0], s.q);
  EXPECT_EQ(s.q->observations.size(), 3u);
  EXPECT_EQ(s.q->observations.at(b), 0);
}

TEST(MatcherFuse, AKeptNewerPointMustAgreeWithTheOlderPointsObservations) {
  Scene s;
  // The other way round: P has more observations than Q, so Q's (in A and C) would go to P; P,
  // 2 m along A's ray, projects 40 px from Q's feature in C.
  const Eigen::Vector3d p_w(0, 0, 2);
  KeyFrame* b1 = AddKeyFrame(&s.map, s.cam, Eigen::Vector3d(0.1, 0, 0.3), p_w, 1);
  KeyFrame* b2 = AddKeyFrame(&s.map, s.cam, Eigen::Vector3d(-0.1, 0, 0.3), p_w, 1);
  KeyFrame* b3 = AddKeyFrame(&s.map, s.cam, Eigen::Vector3d(0, 0.1, 0.3), p_w, 1);
  MapPoint* p = AddPoint(&s.map, p_w, {b1, b2, b3});
  ASSERT_GT((s.cam.Project(s.c->T_c_w * p_w) - s.cam.Project(s.c->T_c_w * s.q->p_w)).norm(), 20.0);

  const Matcher matcher(s.cam, MatcherOptions());
  EXPECT_EQ(matcher.Fuse(s.a, {p}, 3.0), 0);
  EXPECT_FALSE(s.q->bad);
  EXPECT_FALSE(p->bad);
  EXPECT_EQ(s.c->points[0], s.q);
}

}  // namespace
}  // namespace viqu::slam

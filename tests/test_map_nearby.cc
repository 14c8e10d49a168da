// Map::NearbyKeyFrames: the keyframes that the tracker adds to its local map by place (a view
// seen again after a loop), checked on hand-placed keyframes.
#include <set>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "slam/core/map.h"

namespace viqu::slam {
namespace {

// A keyframe with no features whose camera sits at `centre` (world), turned by `yaw_deg` about
// the camera's y axis (0: looking along world +z).
KeyFrame* AddAt(Map* map, const Eigen::Vector3d& centre, double yaw_deg = 0) {
  Frame f;
  f.Reset(std::make_shared<FrameFeatures>());
  Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();
  T_w_c.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T_w_c.translation() = centre;
  f.T_c_w = T_w_c.inverse();
  return map->AddKeyFrame(f);
}

TEST(MapNearby, NearestFirstWithinRadiusAndAngleSkippingBadAndExcluded) {
  Map map;
  KeyFrame* a = AddAt(&map, {0, 0, 0});
  KeyFrame* b = AddAt(&map, {0.3, 0, 0});
  AddAt(&map, {0.1, 0, 0}, 90);             // near, but looking sideways
  AddAt(&map, {1.0, 0, 0});                 // looking the same way, too far
  KeyFrame* bad = AddAt(&map, {0.06, 0, 0});
  bad->bad = true;
  KeyFrame* excluded = AddAt(&map, {0.04, 0, 0});
  KeyFrame* tilted = AddAt(&map, {0.0, 0.2, 0}, 25);  // within 30 degrees
  Eigen::Isometry3d camera = Eigen::Isometry3d::Identity();
  camera.translation() = Eigen::Vector3d(0.05, 0, 0);
  const std::set<KeyFrame*> exclude = {excluded};

  // Distances from (0.05, 0, 0): a 0.05, tilted sqrt(0.05^2 + 0.2^2) = 0.206, b 0.25.
  const std::vector<KeyFrame*> all = map.NearbyKeyFrames(camera, 0.5, 30, exclude, 10);
  EXPECT_EQ(all, (std::vector<KeyFrame*>{a, tilted, b}));
  EXPECT_EQ(map.NearbyKeyFrames(camera, 0.5, 30, exclude, 2), (std::vector<KeyFrame*>{a, tilted}));
  // A radius of 0.22 m leaves b out; 20 degrees leaves the tilted one out.
  EXPECT_EQ(map.NearbyKeyFrames(camera, 0.22, 30, exclude, 10), (std::vector<KeyFrame*>{a, tilted}));
  EXPECT_EQ(map.NearbyKeyFrames(camera, 0.5, 20, exclude, 10), (std::vector<KeyFrame*>{a, b}));
  EXPECT_TRUE(map.NearbyKeyFrames(camera, 0.5, 30, exclude, 0).empty());
}

TEST(MapNearby, EqualDistancesAreOrderedById) {
  Map map;
  KeyFrame* left = AddAt(&map, {-0.1, 0, 0});
  KeyFrame* right = AddAt(&map, {0.1, 0, 0});
  const std::vector<KeyFrame*> near = map.NearbyKeyFrames(Eigen::Isometry3d::Identity(), 0.5, 30, {}, 10);
  ASSERT_EQ(near.size(), 2u);
  EXPECT_EQ(near[0], left);
  EXPECT_EQ(near[1], right);
}

}  // namespace
}  // namespace viqu::slam

// The viewer's window-free parts: playback (pause, step, speed, pacing), the window layout, and
// the paths and map points added to a MuJoCo scene. No display needed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "viewer/map_geoms.h"
#include "viewer/playback.h"
#include "viewer/view_layout.h"

namespace viqu::viewer {
namespace {

TEST(Playback, PausedLetsFramesThroughOnlyByStep) {
  Playback p(1.0);
  EXPECT_TRUE(p.TakeFrame());
  p.TogglePause();
  EXPECT_FALSE(p.TakeFrame());
  EXPECT_FALSE(p.TakeFrame());
  p.Step();
  EXPECT_TRUE(p.paused());
  EXPECT_TRUE(p.TakeFrame());   // exactly one frame per step
  EXPECT_FALSE(p.TakeFrame());
  p.Step();
  p.Step();                     // steps asked for in a row add up: two frames
  EXPECT_TRUE(p.TakeFrame());
  EXPECT_TRUE(p.TakeFrame());
  EXPECT_FALSE(p.TakeFrame());
  p.Step();
  p.TogglePause();              // resuming drops steps not taken
  p.TogglePause();
  EXPECT_FALSE(p.TakeFrame());
  p.TogglePause();
  EXPECT_TRUE(p.TakeFrame());
  Playback start_paused(1.0, true);
  EXPECT_FALSE(start_paused.TakeFrame());
}

TEST(Playback, PacesSimulatedTimeAtTheSpeed) {
  Playback p(2.0);  // 2 simulated s per wall s
  EXPECT_EQ(p.WaitBefore(10.0, 100.0), 0);           // the first frame starts the pace
  EXPECT_NEAR(p.WaitBefore(11.0, 100.0), 0.5, 1e-12);  // 1 simulated s = 0.5 wall s later
  EXPECT_NEAR(p.WaitBefore(11.0, 100.3), 0.2, 1e-12);
  EXPECT_EQ(p.WaitBefore(11.0, 100.6), 0);            // late by 0.1 s: show at once
  // Far behind (a slow stretch): the pace restarts from this frame instead of rushing on.
  EXPECT_EQ(p.WaitBefore(12.0, 103.0), 0);
  EXPECT_NEAR(p.WaitBefore(12.2, 103.0), 0.1, 1e-12);
  p.SetSpeed(0);  // unpaced
  EXPECT_EQ(p.WaitBefore(20.0, 103.0), 0);
  EXPECT_EQ(p.WaitBefore(30.0, 103.0), 0);
  p.SetSpeed(0.5);  // a speed change restarts the pace
  EXPECT_EQ(p.WaitBefore(30.0, 200.0), 0);
  EXPECT_NEAR(p.WaitBefore(30.05, 200.0), 0.1, 1e-12);
}

TEST(Playback, SpeedDoublesAndHalvesWithinLimits) {
  Playback p(1.0);
  p.Faster();
  EXPECT_EQ(p.speed(), 2.0);
  p.Slower();
  p.Slower();
  EXPECT_EQ(p.speed(), 0.5);
  for (int i = 0; i < 20; ++i) p.Faster();
  EXPECT_EQ(p.speed(), Playback::kMaxSpeed);
  for (int i = 0; i < 40; ++i) p.Slower();
  EXPECT_EQ(p.speed(), Playback::kMinSpeed);
  p.SetSpeed(0);
  p.Faster();
  EXPECT_EQ(p.speed(), 0);  // unpaced stays unpaced
  p.Slower();
  EXPECT_EQ(p.speed(), Playback::kMaxSpeed);
  p.SetSpeed(-3);
  EXPECT_EQ(p.speed(), 0);
}

TEST(ViewLayout, ImageTopRightSceneLeftStatusBelow) {
  const ViewLayout l = LayoutFor(1280, 720, 640, 480);
  EXPECT_EQ(l.image_scale, 1.0);
  EXPECT_EQ(l.image.left, 640);
  EXPECT_EQ(l.image.bottom, 240);
  EXPECT_EQ(l.image.width, 640);
  EXPECT_EQ(l.image.height, 480);
  EXPECT_EQ(l.scene.left, 0);
  EXPECT_EQ(l.scene.width, 640);
  EXPECT_EQ(l.scene.height, 720);
  EXPECT_EQ(l.status.left, 640);
  EXPECT_EQ(l.status.height, 240);
  // A small window shrinks the image (aspect kept) and the scene keeps at least half the width.
  const ViewLayout s = LayoutFor(800, 400, 640, 480);
  EXPECT_NEAR(s.image_scale, 0.625, 1e-12);  // 0.75 * 400 / 480
  EXPECT_EQ(s.image.width, 400);
  EXPECT_EQ(s.image.height, 300);
  EXPECT_EQ(s.image.left + s.image.width, 800);
  EXPECT_EQ(s.image.bottom + s.image.height, 400);
  EXPECT_GE(s.scene.width, 400);
  // A minimised window (0 x 0) draws nothing and does not divide by zero.
  const ViewLayout z = LayoutFor(0, 0, 640, 480);
  EXPECT_EQ(z.image_scale, 0);
  EXPECT_EQ(z.scene.width, 0);
}

TEST(MapGeoms, ThinPathKeepsEndsAndBoundsTheSegments) {
  EXPECT_TRUE(ThinPath(0, 10).empty());
  EXPECT_EQ(ThinPath(1, 10), std::vector<int>({0}));
  EXPECT_EQ(ThinPath(5, 10), std::vector<int>({0, 1, 2, 3, 4}));
  for (int n : {11, 400, 401, 1000, 12345}) {
    const std::vector<int> k = ThinPath(n, 100);
    EXPECT_EQ(k.front(), 0);
    EXPECT_EQ(k.back(), n - 1);
    EXPECT_LE(static_cast<int>(k.size()) - 1, 100) << n;
    EXPECT_GE(static_cast<int>(k.size()) - 1, std::min(n - 1, 50)) << n;  // not thinned more than needed
    for (size_t i = 1; i < k.size(); ++i) EXPECT_LT(k[i - 1], k[i]);
  }
}

// A scene made for a model of one geom, as the viewer makes it (the scene needs a model).
class SceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::filesystem::path xml = std::filesystem::temp_directory_path() / "viqu_test_viewer_box.xml";
    std::ofstream(xml) << "<mujoco><worldbody><geom type='box' size='1 1 1'/></worldbody></mujoco>";
    char err[256] = "";
    m_ = mj_loadXML(xml.c_str(), nullptr, err, sizeof(err));
    ASSERT_NE(m_, nullptr) << err;
    mjv_defaultScene(&scn_);
    mjv_makeScene(m_, &scn_, 20);
  }
  void TearDown() override {
    mjv_freeScene(&scn_);
    if (m_) mj_deleteModel(m_);
  }
  mjModel* m_ = nullptr;
  mjvScene scn_;
};

TEST_F(SceneTest, PathsBecomeLinesBetweenTheirPointsAndMapPointsBoxes) {
  MapDrawing d;
  MapDrawing::Path path;
  path.points = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
  path.rgba[1] = 0.5f;
  d.paths.push_back(path);
  d.map_points = {{3, 4, 5}, {-1, -2, -3}};
  d.on_object = {0, 1};
  MapStyle style;
  const int added = AddMapGeoms(d, style, &scn_);
  ASSERT_EQ(added, 4);  // 2 segments + 2 points
  ASSERT_EQ(scn_.ngeom, 4);
  // Segment 2 runs from (1,0,0) to (1,2,0). MuJoCo draws a line from pos along the geom's z
  // axis (third column of the row-major mat) for size[2] metres.
  const mjvGeom& seg = scn_.geoms[1];
  EXPECT_EQ(seg.type, mjGEOM_LINE);
  EXPECT_NEAR(seg.pos[0], 1, 1e-6);
  EXPECT_NEAR(seg.pos[1], 0, 1e-6);
  EXPECT_FLOAT_EQ(seg.rgba[1], 0.5f);
  EXPECT_NEAR(seg.mat[5], 1, 1e-6);  // z axis along +y
  EXPECT_NEAR(seg.size[2], 2, 1e-5);
  const mjvGeom& p0 = scn_.geoms[2];
  EXPECT_EQ(p0.type, mjGEOM_BOX);
  EXPECT_FLOAT_EQ(p0.pos[0], 3);
  EXPECT_FLOAT_EQ(p0.pos[2], 5);
  EXPECT_FLOAT_EQ(p0.size[0], static_cast<float>(style.point_half_size_m));
  EXPECT_FLOAT_EQ(p0.rgba[2], style.point_rgba[2]);
  EXPECT_FLOAT_EQ(scn_.geoms[3].rgba[0], style.object_point_rgba[0]);  // made on an object
}

TEST_F(SceneTest, OnlyWhatFitsIsAddedNewestMapPointsFirst) {
  MapDrawing d;
  for (int i = 0; i < 50; ++i) d.map_points.push_back({static_cast<double>(i), 0, 0});
  MapStyle style;
  style.max_map_points = 30;
  scn_.ngeom = 5;  // the model's own geoms are already in (maxgeom 20 + the model's 1)
  const int room = scn_.maxgeom - 5;
  EXPECT_EQ(AddMapGeoms(d, style, &scn_), room);
  EXPECT_EQ(scn_.ngeom, scn_.maxgeom);
  EXPECT_FLOAT_EQ(scn_.geoms[5].pos[0], 20);  // the 30 newest are 20..49; the first that fit
  EXPECT_EQ(AddMapGeoms(d, style, &scn_), 0);  // full: nothing more, no overflow
}

}  // namespace
}  // namespace viqu::viewer

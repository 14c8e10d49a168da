// The indoor worlds in models/worlds/: each loads without MuJoCo warnings inside a minimal
// wrapper, follows the naming conventions, keeps to two shadowless lights, and, seen from the
// robot's camera about 7 cm above the floor, is textured richly enough for ORB/FAST features.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/mujoco_handles.h"
#include "sim/scene_composer.h"
#include "sim/terrain.h"
#include "sim/stereo_renderer.h"

namespace viqu::sim {
namespace {

const std::string kWorlds = std::string(VIQU_SOURCE_DIR) + "/models/worlds/";

std::vector<std::string> WorldFiles() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(kWorlds))
    if (e.path().extension() == ".xml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Worlds, EachLoadsAndFollowsTheConventions) {
  const std::vector<std::string> files = WorldFiles();
  ASSERT_GE(files.size(), 3u);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    TakeMujocoWarnings();
    ModelPtr m = LoadModelString("<mujoco>\n" + InlineMjcfPiece(file) + "\n</mujoco>\n", file);
    EXPECT_TRUE(TakeMujocoWarnings().empty());
    EXPECT_GE(mj_name2id(m.get(), mjOBJ_GEOM, "floor"), 0) << "a plane geom named floor";
    EXPECT_LE(m->nlight, 2);
    for (int i = 0; i < m->nlight; ++i) EXPECT_FALSE(m->light_castshadow[i]);
    for (int b = 1; b < m->nbody; ++b) {
      const std::string name = MjName(m.get(), mjOBJ_BODY, b);
      EXPECT_EQ(m->body_parentid[b], 0) << name;
      EXPECT_EQ(name.rfind("furniture:", 0), 0u) << "static props are furniture:NAME, got " << name;
    }
  }
}

struct View {
  const char* world;
  double x, y, yaw_deg;  // robot trunk pose
};

// Poses along the scenario paths (room square, corridor lanes, hall loop), looking in the
// directions the robot walks and at the walls.
const View kViews[] = {
    {"room.xml", -1, -1, 0},       {"room.xml", 1, -1, 90},       {"room.xml", 1, 1, 180},
    {"room.xml", -1, 1, -90},      {"room.xml", 0, 0, -135},      {"corridor.xml", 0.5, -0.55, 0},
    {"corridor.xml", 13.5, -0.55, 90}, {"corridor.xml", 13.5, 0.55, 180},
    {"corridor.xml", 10, 0, -90},  {"room_large.xml", -3.2, -2.2, 0},
    {"room_large.xml", 3.2, 2.2, 180}, {"room_large.xml", -3.2, 0, -90},
};

TEST(Worlds, ViewsFromTheRobotHaveManyFastCorners) {
  const std::string rat = std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.xml";
  std::string loaded;
  ModelPtr m;
  DataPtr d;
  std::unique_ptr<StereoRenderer> renderer;
  for (const View& v : kViews) {
    if (loaded != v.world) {
      renderer.reset();
      Scenario s;
      s.name = "worlds";
      s.world = kWorlds + v.world;
      s.robot.model = rat;
      m = LoadModelString(ComposeSceneXml(s, SceneHeader{}, {}), s.world);
      d.reset(mj_makeData(m.get()));
      RenderOptions opt;
      opt.depth = false;
      opt.segmentation = false;
      renderer = std::make_unique<StereoRenderer>(m.get(), opt);
      loaded = v.world;
    }
    // The floor is drawn where the robot stands (MuJoCo collides with a plane everywhere but draws
    // it only over its size: the corridor's far half was a black void until session 45).
    const std::optional<FloorExtent> floor = FloorExtentOf(m.get());
    ASSERT_TRUE(floor.has_value()) << v.world;
    EXPECT_TRUE(floor->Holds({v.x, v.y})) << v.world << " at " << v.x << ", " << v.y << ": no floor drawn there";
    const double yaw = v.yaw_deg * M_PI / 180;
    const int root = m->jnt_qposadr[MjIdOrThrow(m.get(), mjOBJ_JOINT, "root", "rat")];
    mjtNum* q = d->qpos + root;
    q[0] = v.x, q[1] = v.y, q[2] = 0.075;
    q[3] = std::cos(yaw / 2), q[4] = 0, q[5] = 0, q[6] = std::sin(yaw / 2);
    mj_forward(m.get(), d.get());
    StereoFrame f;
    renderer->Render(m.get(), d.get(), &f);
    cv::Mat grey;
    cv::cvtColor(f.left_rgb, grey, cv::COLOR_RGB2GRAY);
    std::vector<cv::KeyPoint> corners;
    cv::FAST(grey, corners, 20);
    std::printf("%s at (%g, %g, %g deg): %zu FAST corners\n", v.world, v.x, v.y, v.yaw_deg,
                corners.size());
    EXPECT_GE(corners.size(), 300u) << v.world << " at " << v.x << ", " << v.y;
  }
}

}  // namespace
}  // namespace viqu::sim

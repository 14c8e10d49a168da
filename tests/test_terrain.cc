// Terrain: friction patches and slopes as MJCF geoms.
#include "sim/terrain.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "sim/mujoco_handles.h"

namespace viqu::sim {
namespace {

TerrainConfig Example() {
  TerrainConfig t;
  t.friction = 0.9;
  t.patches.push_back({{1.0, 0.5}, {0.6, 0.4}, 0.05});
  t.patches.push_back({{-1.0, -0.5}, {0.5, 0.5}, 0.2});
  t.slopes.push_back({{0.0, 2.0}, {1.0, 0.6}, 8.0, 30.0});
  t.slopes.push_back({{-2.0, 1.0}, {0.8, 0.5}, 5.0, 180.0});
  return t;
}

ModelPtr Load(const TerrainConfig& t) {
  const std::string xml =
      "<mujoco><worldbody><geom name=\"floor\" type=\"plane\" size=\"5 5 .1\"/></worldbody>\n" +
      TerrainXml(t) + "</mujoco>\n";
  return LoadModelString(xml, "test_terrain");
}

// Height of the first surface below (x, y, 1), by a ray straight down; the ray's hit geom too.
double SurfaceZ(const mjModel* m, const mjData* d, double x, double y, int* geom) {
  const mjtNum from[3] = {x, y, 1.0}, down[3] = {0, 0, -1};
  const mjtNum dist = mj_ray(m, d, from, down, nullptr, 1, -1, geom);
  return 1.0 - dist;
}

TEST(Terrain, LoadsWithoutWarnings) {
  TakeMujocoWarnings();
  ModelPtr m = Load(Example());
  EXPECT_TRUE(TakeMujocoWarnings().empty());
  EXPECT_EQ(TerrainXml(TerrainConfig{}), "");
}

TEST(Terrain, PatchesCarryTheirFrictionJustAboveTheFloor) {
  const TerrainConfig t = Example();
  ModelPtr m = Load(t);
  DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  for (size_t i = 0; i < t.patches.size(); ++i) {
    const std::string name = "terrain_patch_" + std::to_string(i);
    const int id = mj_name2id(m.get(), mjOBJ_GEOM, name.c_str());
    ASSERT_GE(id, 0) << name;
    EXPECT_DOUBLE_EQ(m->geom_friction[3 * id], t.patches[i].friction);
    EXPECT_GE(m->geom_matid[id], 0) << "patches are textured";
    // The top surface covers the patch's rectangle, kPatchTop_m above the floor, not beyond it.
    const FrictionPatch& p = t.patches[i];
    int hit = -1;
    const double inside = SurfaceZ(m.get(), d.get(), p.center[0] + 0.45 * p.size[0],
                                   p.center[1] - 0.45 * p.size[1], &hit);
    EXPECT_EQ(hit, id);
    EXPECT_NEAR(inside, kPatchTop_m, 1e-6);
    const double outside = SurfaceZ(m.get(), d.get(), p.center[0] + 0.55 * p.size[0],
                                    p.center[1], &hit);
    EXPECT_EQ(hit, mj_name2id(m.get(), mjOBJ_GEOM, "floor"));
    EXPECT_NEAR(outside, 0.0, 1e-9);
  }
}

TEST(Terrain, SlopeRisesAtItsAngleFromTheFloor) {
  const TerrainConfig t = Example();
  ModelPtr m = Load(t);
  DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  for (size_t i = 0; i < t.slopes.size(); ++i) {
    const Slope& s = t.slopes[i];
    const std::string name = "terrain_slope_" + std::to_string(i);
    const int id = mj_name2id(m.get(), mjOBJ_GEOM, name.c_str());
    ASSERT_GE(id, 0) << name;
    EXPECT_DOUBLE_EQ(m->geom_friction[3 * id], t.friction);
    const double a = s.angle_deg * M_PI / 180, yaw = s.yaw_deg * M_PI / 180;
    const double run = s.size[0] * std::cos(a);  // horizontal length of the top surface
    // Foot of the ramp: half its horizontal length behind the centre, along the ascent.
    const double fx = s.center[0] - 0.5 * run * std::cos(yaw);
    const double fy = s.center[1] - 0.5 * run * std::sin(yaw);
    for (double frac : {0.1, 0.35, 0.6, 0.9}) {
      const double dist = frac * run;
      // Also off the centre line, across the ramp.
      const double across = 0.3 * s.size[1];
      const double x = fx + dist * std::cos(yaw) - across * std::sin(yaw);
      const double y = fy + dist * std::sin(yaw) + across * std::cos(yaw);
      int hit = -1;
      EXPECT_NEAR(SurfaceZ(m.get(), d.get(), x, y, &hit), std::tan(a) * dist, 1e-3)
          << name << " at " << frac;
      EXPECT_EQ(hit, id);
    }
    // Before the foot, the floor.
    int hit = -1;
    const double z = SurfaceZ(m.get(), d.get(), fx - 0.05 * std::cos(yaw),
                              fy - 0.05 * std::sin(yaw), &hit);
    EXPECT_NEAR(z, 0.0, 1e-9);
  }
}

TEST(Terrain, FloorFrictionIsSet) {
  ModelPtr m = Load(Example());
  ApplyFloorFriction(m.get(), 0.7);
  EXPECT_DOUBLE_EQ(m->geom_friction[3 * mj_name2id(m.get(), mjOBJ_GEOM, "floor")], 0.7);
  EXPECT_THROW(ApplyFloorFriction(m.get(), 0.0), InputError);
  ModelPtr bare = LoadModelString("<mujoco><worldbody><geom type=\"plane\" size=\"1 1 .1\"/>"
                                  "</worldbody></mujoco>", "bare");
  EXPECT_THROW(ApplyFloorFriction(bare.get(), 0.7), InputError);
}

TEST(Terrain, RejectsOutOfRangeValues) {
  TerrainConfig t = Example();
  t.patches[0].friction = -1;
  EXPECT_THROW(TerrainXml(t), InputError);
  t = Example();
  t.slopes[0].angle_deg = 45;
  EXPECT_THROW(TerrainXml(t), InputError);
  t.slopes[0].angle_deg = 0;
  EXPECT_THROW(TerrainXml(t), InputError);
}

TEST(Terrain, NegativeAngleDescendsAlongYaw) {
  TerrainConfig up, down;
  up.slopes.push_back({{0.5, -0.5}, {1.0, 0.6}, 7.0, 200.0});
  down.slopes.push_back({{0.5, -0.5}, {1.0, 0.6}, -7.0, 20.0});
  EXPECT_EQ(TerrainXml(up), TerrainXml(down));
}

}  // namespace
}  // namespace viqu::sim

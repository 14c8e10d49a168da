// Warnings about valid scenarios that are likely not what their author meant
// (runner/scenario_warnings.h), and the world's floor they are judged against.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runner/scenario_warnings.h"
#include "sim/mujoco_handles.h"
#include "sim/terrain.h"

namespace viqu {
namespace {

bool Has(const std::vector<std::string>& w, const std::string& text) {
  for (const std::string& line : w) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(ScenarioWarnings, TheRoomsFloorIsItsPlane) {
  const sim::ModelPtr m = sim::LoadModelFile(std::string(VIQU_SOURCE_DIR) + "/models/worlds/room.xml");
  const std::optional<sim::FloorExtent> f = sim::FloorExtentOf(m.get());
  ASSERT_TRUE(f.has_value());
  // room.xml: <geom name="floor" type="plane" size="3 2.5 0.1"> at the origin.
  EXPECT_NEAR(f->x_min, -3, 1e-12);
  EXPECT_NEAR(f->x_max, 3, 1e-12);
  EXPECT_NEAR(f->y_min, -2.5, 1e-12);
  EXPECT_NEAR(f->y_max, 2.5, 1e-12);
  // An unbounded plane (size 0) has no extent.
  const sim::ModelPtr open = sim::LoadModelString(
      "<mujoco><worldbody><geom name=\"floor\" type=\"plane\" size=\"0 0 1\"/></worldbody></mujoco>", "open floor");
  EXPECT_FALSE(sim::FloorExtentOf(open.get()).has_value());
}

TEST(ScenarioWarnings, NameWhatHasNoEffectOrLiesOffTheFloor) {
  Scenario s;
  s.duration_s = 5;
  s.sensors.camera.dropouts = {{1, 2}, {6, 8}};
  s.disturbances.resize(2);
  s.disturbances[0].t_s = 4.9;
  s.disturbances[1].t_s = 7;
  s.robot.start.xy = {-1, -1};
  s.robot.command.waypoints = {{1, 1}, {5, 0}};
  ObstacleConfig walker;
  walker.name = "walker";
  walker.path = {{1, -0.8}, {1, 4}};
  s.obstacles.push_back(walker);
  const sim::FloorExtent room{-3, 3, -2.5, 2.5};
  const std::vector<std::string> w = runner::ScenarioWarnings(s, "adaptive", room);
  for (const std::string& line : w) std::printf("%s\n", line.c_str());
  EXPECT_EQ(w.size(), 4u);
  EXPECT_TRUE(Has(w, "sensors.camera.dropouts.1 starts at 6 s, at or after the run's end (duration_s 5)"));
  EXPECT_TRUE(Has(w, "disturbances.1 starts at 7 s"));
  EXPECT_TRUE(Has(w, "robot.command.waypoints.1 (5, 0) lies outside the world's floor (x -3 to 3, y -2.5 to 2.5 m)"));
  EXPECT_TRUE(Has(w, "obstacles.0.path.1 (1, 4) (walker) lies outside"));
  // The dynamic stage without masks; a start off the floor; nothing said without a floor extent
  // or a dynamic stage.
  s.sensors.camera.segmentation = false;
  s.robot.start.xy = {-100, -100};
  const std::vector<std::string> w2 = runner::ScenarioWarnings(s, "adaptive", room);
  EXPECT_TRUE(Has(w2, "slam.dynamic.method adaptive judges objects by their instance masks, but "
                      "sensors.camera.segmentation is false"));
  EXPECT_TRUE(Has(w2, "robot.start.xy (-100, -100) lies outside"));
  EXPECT_EQ(runner::ScenarioWarnings(s, "", std::nullopt).size(), 2u);  // the two past the end
  // Steering on the estimate needs waypoints: a velocity schedule is open loop.
  s.robot.command.follow = "estimate";
  EXPECT_FALSE(Has(runner::ScenarioWarnings(s, "", std::nullopt), "robot.command.follow"));
  s.robot.command.waypoints.clear();
  s.robot.command.velocity = {VelocityCommand{0, 0.1, 0}};
  EXPECT_TRUE(Has(runner::ScenarioWarnings(s, "", std::nullopt),
                  "robot.command.follow: estimate steers waypoints; the velocity schedule is open loop"));
}

}  // namespace
}  // namespace viqu

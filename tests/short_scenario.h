#pragma once
// A one-second scenario for tests of the run loop: the robot walks a gentle curve in the room at
// 320 x 240 while one person crosses the view. Header-only, shared by the run-loop tests.
#include <cstdint>
#include <string>

#include "scenario/scenario.h"

namespace viqu::testing {

inline Scenario ShortWalkerScenario(const std::string& name, uint64_t seed) {
  Scenario s;
  s.name = name;
  s.seed = seed;
  s.duration_s = 1.0;
  s.world = std::string(VIQU_SOURCE_DIR) + "/models/worlds/room.xml";
  s.robot.model = std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.xml";
  s.robot.command.velocity = {{0.0, 0.12, 0.2}};
  s.sensors.camera.width = 320;
  s.sensors.camera.height = 240;
  ObstacleConfig person;
  person.name = "walker";
  person.category = "person";
  person.path = {{1.0, -0.8}, {1.0, 0.8}};
  person.speed_mps = 0.8;
  s.obstacles.push_back(person);
  return s;
}

}  // namespace viqu::testing

#include "runner/scenario_warnings.h"

#include <cstdio>

namespace viqu::runner {
namespace {

std::string Num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

std::string Point(const Vec2& p) { return "(" + Num(p[0]) + ", " + Num(p[1]) + ")"; }

}  // namespace

std::vector<std::string> ScenarioWarnings(const Scenario& s, const std::string& dynamic_method,
                                          const std::optional<sim::FloorExtent>& floor) {
  std::vector<std::string> w;
  const std::string end = "the run's end (duration_s " + Num(s.duration_s) + ")";
  for (size_t i = 0; i < s.sensors.camera.dropouts.size(); ++i) {
    const double t0 = s.sensors.camera.dropouts[i][0];
    if (t0 >= s.duration_s) {
      w.push_back("sensors.camera.dropouts." + std::to_string(i) + " starts at " + Num(t0) + " s, at or after " + end +
                  ": it has no effect");
    }
  }
  for (size_t i = 0; i < s.disturbances.size(); ++i) {
    if (s.disturbances[i].t_s >= s.duration_s) {
      w.push_back("disturbances." + std::to_string(i) + " starts at " + Num(s.disturbances[i].t_s) + " s, at or after " +
                  end + ": it has no effect");
    }
  }
  if (s.robot.command.waypoints.empty() && s.robot.command.velocity.empty()) {
    w.push_back("robot.command has no waypoints and no velocity schedule: the robot stands still for the whole run");
  } else if (s.robot.command.follow == "estimate" && s.robot.command.waypoints.empty()) {
    w.push_back("robot.command.follow: estimate steers waypoints; the velocity schedule is open loop, so it has no "
                "effect");
  }
  if (!dynamic_method.empty() && !s.sensors.camera.segmentation) {
    w.push_back("slam.dynamic.method " + dynamic_method +
                " judges objects by their instance masks, but sensors.camera.segmentation is false: no object is judged");
  }
  if (floor) {
    const std::string where = "outside the world's floor (x " + Num(floor->x_min) + " to " + Num(floor->x_max) + ", y " +
                              Num(floor->y_min) + " to " + Num(floor->y_max) + " m)";
    if (!floor->Holds(s.robot.start.xy)) w.push_back("robot.start.xy " + Point(s.robot.start.xy) + " lies " + where);
    for (size_t i = 0; i < s.robot.command.waypoints.size(); ++i) {
      const Vec2& p = s.robot.command.waypoints[i];
      if (!floor->Holds(p)) w.push_back("robot.command.waypoints." + std::to_string(i) + " " + Point(p) + " lies " + where);
    }
    for (size_t i = 0; i < s.obstacles.size(); ++i) {
      for (size_t k = 0; k < s.obstacles[i].path.size(); ++k) {
        const Vec2& p = s.obstacles[i].path[k];
        if (!floor->Holds(p)) {
          w.push_back("obstacles." + std::to_string(i) + ".path." + std::to_string(k) + " " + Point(p) + " (" +
                      s.obstacles[i].name + ") lies " + where);
        }
      }
    }
  }
  return w;
}

}  // namespace viqu::runner

#pragma once
// Scripted obstacles: people, boxes, balls and movable furniture moved along waypoint paths.
//
// ObstaclePath is the timing of one obstacle as a pure function of time (tested exactly);
// ObstaclesXml writes the MJCF bodies (kinematic mocap bodies, named CATEGORY:NAME[/PART] as in
// docs/CONVENTIONS.md); ObstacleSet moves those bodies and gives the ground truth of every
// obstacle (pose and whether it moves) at any instant.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

#include "scenario/scenario.h"

namespace viqu::sim {

// Where one obstacle is at time t (s of simulated time), from its ObstacleConfig:
// - it stands at path[0], heading yaw_deg, until start_s;
// - then walks the waypoints in order at speed_mps, and waits pause_s at every waypoint reached;
// - loop "none": stops for good at the last waypoint; "loop": walks back to path[0] and starts
//   over; "pingpong": walks the path backwards to path[0] and starts over;
// - a single-point path never moves.
// While walking, the heading faces the direction of motion; while paused it keeps the heading of
// the leg it arrived on. Throws viqu::InputError on an invalid configuration.
class ObstaclePath {
 public:
  explicit ObstaclePath(const ObstacleConfig& cfg);

  // One straight stretch between two waypoints, followed by a wait.
  struct Leg {
    Eigen::Vector2d from_w, to_w;  // world xy (m)
    double begin_s = 0;            // start time within the cycle (s), relative to start_s
    double walk_s = 0;             // walking time (s)
    double pause_s = 0;            // wait after arriving (s)
    double length_m = 0;           // |to - from| (m)
    double distance_before_m = 0;  // distance walked within the cycle before this leg (m)
    double yaw_rad = 0;            // heading while walking it (rad)
  };

  // Position of time t on the path.
  struct Where {
    bool before_start = true;  // t < start_s (or the path has no legs)
    bool finished = false;     // loop "none" and the last waypoint reached
    long cycle = 0;            // completed cycles (loop / pingpong)
    int leg = -1;              // index into legs(), -1 before the start
    double fraction = 0;       // walked fraction of the leg, [0, 1]
    bool moving = false;       // walking (not standing, pausing or finished)
  };

  Where Locate(double t) const;
  Eigen::Vector2d Position(double t) const;  // world xy (m)
  double Yaw(double t) const;                // heading (rad), world z
  bool Moving(double t) const;
  double Distance(double t) const;           // metres walked since start_s

  const std::vector<Leg>& legs() const { return legs_; }
  double cycle_s() const { return cycle_s_; }         // duration of one cycle (s)
  double cycle_length_m() const { return cycle_m_; }  // distance of one cycle (m)

 private:
  Eigen::Vector2d start_w_;
  double start_s_ = 0;
  double yaw0_rad_ = 0;
  bool repeats_ = false;  // loop or pingpong
  std::vector<Leg> legs_;
  double cycle_s_ = 0;
  double cycle_m_ = 0;
};

// MJCF text (an <asset> and a <worldbody> section; MJCF allows repeated sections) with one
// mocap body per obstacle, named CATEGORY:NAME, plus person:NAME/leg_l and person:NAME/leg_r for
// people. Bodies start at their t = 0 pose. Textures are referenced by absolute path.
// Empty string for no obstacles. Throws viqu::InputError on an invalid configuration.
std::string ObstaclesXml(const std::vector<ObstacleConfig>& obstacles);

// Moves the mocap bodies of ObstaclesXml and reports the ground truth.
class ObstacleSet {
 public:
  // Throws viqu::InputError if a body is missing from the model or is not a mocap body.
  ObstacleSet(const mjModel* m, const std::vector<ObstacleConfig>& cfg);

  // Sets mocap_pos / mocap_quat of every part for time t (s). Legs swing with a phase taken from
  // the distance walked; balls roll without slipping.
  void Apply(const mjModel* m, mjData* d, double t) const;

  struct State {
    std::string name;      // instance name (from the scenario)
    std::string category;  // person | box | ball | furniture
    Eigen::Vector3d p_w;   // position of the root body in world (m): person at floor level
    Eigen::Quaterniond q_w;  // orientation of the root body in world
    bool moving = false;
  };
  std::vector<State> StateAt(double t) const;

 private:
  struct Part {
    int mocap_id = -1;
    Eigen::Vector3d p_o;  // part origin in the obstacle frame at zero swing (m)
    double swing_sign = 0;  // +1 / -1 for legs, 0 for rigid parts
  };
  struct Item {
    ObstacleConfig cfg;
    ObstaclePath path;
    std::vector<Part> parts;  // parts[0] is the root body
    double z_m = 0;           // height of the root body origin (m)
    double radius_m = 0;      // balls: rolling radius (m)
  };
  static Eigen::Quaterniond RollingQuat(const Item& item, double t);
  void PartPose(const Item& item, const Part& part, double t, Eigen::Vector3d* p_w,
                Eigen::Quaterniond* q_w) const;
  std::vector<Item> items_;
};

}  // namespace viqu::sim

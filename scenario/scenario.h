#pragma once
// The scenario: everything one run needs, as plain structs with units. Filled by
// LoadScenario (scenario_loader.h), which validates every key; defaults below are the values a
// key takes when the YAML leaves it out. Key names in comments are the YAML keys (DESIGN.md).
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace viqu {

using Vec2 = std::array<double, 2>;

struct GaitConfig {                  // robot.gait
  std::string type = "trot";         // trot | walk
  double frequency_hz = 3.0;         // gait cycles per second (Hz)
  double duty = 0.6;                 // stance fraction of a cycle, (0, 1)
  double step_height_m = 0.015;      // swing apex above the stance height (m)
};

// One entry of a velocity schedule: from t_s on, walk with this command (until the next entry).
struct VelocityCommand {
  double t_s = 0;                    // start time (s)
  double forward_mps = 0;            // forward speed (m/s)
  double yaw_rate_dps = 0;           // yaw rate (deg/s), positive turns left
};

struct CommandConfig {               // robot.command
  std::vector<Vec2> waypoints;       // world xy (m); empty means the velocity schedule is used
  double speed_mps = 0.12;           // cruise speed along waypoints (m/s)
  std::string follow = "ground_truth";  // ground_truth | estimate
  bool loop = false;                 // start over at the first waypoint after the last
  std::vector<VelocityCommand> velocity;  // robot.command.velocity: [{t_s, forward_mps, yaw_rate_dps}]
};

struct StartConfig {                 // robot.start
  Vec2 xy{0, 0};                     // trunk centre in world (m)
  double yaw_deg = 0;                // heading, 0 = world +x (deg)
};

struct RobotConfig {                 // robot
  std::string model;                 // MJCF path (absolute after loading); URDF is beside it, same stem
  StartConfig start;
  GaitConfig gait;
  CommandConfig command;
  bool allow_fall = false;           // robot.allow_fall: if false, a fall ends the run with exit 1
};

struct CameraConfig {                // sensors.camera
  double rate_hz = 20;               // (Hz)
  int width = 640, height = 480;     // (px)
  std::string size_where;            // where the smaller side's width/height was written (FILE:LINE:COL or
                                     // "--set ..."), for messages; empty: the defaults
  double fovy_deg = 70;              // vertical field of view (deg)
  double baseline_m = 0.04;          // stereo baseline (m)
  double noise_std = 2.0;            // Gaussian pixel noise, std in 8-bit grey levels
  bool depth = true;                 // render metric depth for the left camera
  bool segmentation = true;          // render the instance segmentation for the left camera
  // Camera outages: [t0_s, t1_s] intervals in which both images are black (a covered lens, a
  // dropped video link); the frames still come, with nothing to see.
  std::vector<Vec2> dropouts;
};

struct ImuConfig {                   // sensors.imu
  double rate_hz = 200;              // (Hz)
  double accel_noise = 0.02;         // white noise std per sample (m/s^2)
  double gyro_noise = 0.002;         // white noise std per sample (rad/s)
  double accel_bias_walk = 0.001;    // bias random walk (m/s^2/sqrt(s))
  double gyro_bias_walk = 0.0001;    // bias random walk (rad/s/sqrt(s))
  // What one reading holds: "instant", the physics state at the reading (it aliases the contacts'
  // millisecond jolts), or "mean", the mean of the physics steps since the last reading (a MEMS
  // IMU's decimation filter: its delta-velocity over the interval, divided by it).
  std::string sampling = "instant";
};

struct JointsConfig {                // sensors.joints
  double rate_hz = 200;              // (Hz)
  double noise_rad = 0.001;          // white noise std (rad)
  double resolution_rad = 0.0015;    // encoder quantisation step (rad); 0 = none (~12 bit)
  // Joint torque sensing, the servos' motor current read as torque (sim/torque_model.h). The
  // servos saturate at 0.6 N m (models/rat/rat.xml forcerange); the defaults are a hobby servo's
  // current sense: about 1% of that range as noise, a 10-bit reading over it, a bias of half the
  // noise per joint. Not measured against a real servo: set them from its data sheet.
  double torque_noise_nm = 0.005;        // white noise std (N m)
  double torque_resolution_nm = 0.001;   // quantisation step (N m); 0 = none
  double torque_bias_nm = 0.0025;        // std of each joint's constant offset, drawn once a run (N m)
  double torque_delay_s = 0;             // the reading is the torque this long before it, rounded to
                                         // whole encoder periods (s)
  // "instant": the torque of the last physics step (one step behind the encoder's position, see
  // sim::World::JointTorques); "mean": the mean over the physics steps since the last reading (a
  // current sensor's low-pass, or a servo that averages between reports).
  std::string torque_sampling = "instant";
};

struct TouchConfig {                 // sensors.touch: foot touch sensors, read with the encoders
  double threshold_n = 0.5;          // a foot reads "in contact" when its measured normal force exceeds this (N)
  double noise_n = 0.1;              // white noise std on the normal force (N)
};

struct SegmentationConfig {          // sensors.segmentation (steps in sim/segmentation_model.h)
  double miss_rate = 0.05;           // probability that an instance is missing from a frame
  int dilate_px = 2;                 // mask dilation (px), imitates a detector's loose masks
  int latency_frames = 0;            // masks arrive this many camera frames late
  int min_area_px = 150;             // instances with fewer visible pixels are not detected (px)
  double false_positive_rate = 0;    // probability per frame of one spurious mask on the background
  double wrong_category_rate = 0;    // probability per instance and frame of a wrong category
  int boundary_jitter_px = 1;        // masks grow or shrink by up to this much per frame (px)
};

struct SensorsConfig {
  CameraConfig camera;
  ImuConfig imu;
  JointsConfig joints;
  TouchConfig touch;
  SegmentationConfig segmentation;
};

struct ObstacleConfig {              // obstacles[i]
  std::string name;                  // unique
  std::string category = "box";      // person | box | ball | furniture
  std::vector<double> size_m;        // box: [x, y, z] full size; ball: [diameter]; person: [height]
  std::vector<Vec2> path;            // world xy waypoints (m); one point = never moves
  double speed_mps = 0.5;            // speed along the path (m/s)
  double start_s = 0;                // stands still at path[0] until then (s)
  double pause_s = 0;                // waits this long at every waypoint (s)
  std::string loop = "none";         // none | loop | pingpong
  double yaw_deg = 0;                // heading while standing before the start (deg)
};

struct FrictionPatch {               // terrain.patches[i]
  Vec2 center{0, 0};                 // (m)
  Vec2 size{0.5, 0.5};               // full size x, y (m)
  double friction = 0.05;            // sliding friction coefficient
};

struct Slope {                       // terrain.slopes[i]: a ramp rising along its yaw direction
  Vec2 center{0, 0};                 // centre of the ramp (m)
  Vec2 size{1.0, 0.6};               // length along the slope, width (m)
  double angle_deg = 8;              // inclination (deg)
  double yaw_deg = 0;                // direction of ascent in world (deg)
};

struct Disturbance {                 // disturbances[i]: an external push on the trunk
  double t_s = 0;                    // start (s)
  std::array<double, 3> force_n{};   // force at the trunk's centre of mass, world frame (N)
  double duration_s = 0.1;           // (s)
};

struct TerrainConfig {
  double friction = 1.0;             // terrain.friction: floor friction elsewhere
  std::vector<FrictionPatch> patches;
  std::vector<Slope> slopes;
};

// slam.dynamic (paper eqs. 1-4). The same keys live in the SLAM settings (`dynamic.*`, units and
// meaning in slam/config/default.yaml); keys given in the scenario override the settings file.
struct DynamicConfig {
  std::string method = "adaptive";   // none | semantic | paper | adaptive
  double alpha = 1.0, beta = 1.0, gamma = 0.5, th_d = 0.1;
  double window_s = 6;
  int window_n = 10;
  // The other `slam.dynamic.*` keys present in the scenario (`forget_s`, `keep_past_observations`,
  // `prior.<category>`, `adaptive.<key>`; path below dynamic, value as written), in file order:
  // settings of the SLAM settings file's block dynamic for this scenario.
  std::vector<std::pair<std::string, std::string>> more;
};

struct SlamConfig {                  // slam
  std::string mode = "full";         // visual | visual_dynamic | full
  std::string config;                // settings file; empty = slam/config/default.yaml
  DynamicConfig dynamic;
  // `slam.lo.*` keys present in the scenario (key, value as written), in file order: leg-odometry
  // settings (slam/config/default.yaml, block lo) for this scenario.
  std::vector<std::pair<std::string, std::string>> lo;
  // `slam.stereo.*` keys present in the scenario (key, value as written), in file order: the
  // stereo matcher's and the near observations' settings (slam/config/default.yaml, block stereo).
  std::vector<std::pair<std::string, std::string>> stereo;
  // The `slam.mode` / `slam.dynamic.*` / `slam.lo.*` / `slam.stereo.*` keys present in the scenario, as
  // SLAM-settings overrides ("mode=full", "dynamic.alpha=1.5"), applied on top of the settings
  // file in that order.
  std::vector<std::string> settings_overrides;
  // Where each of settings_overrides was read ("FILE:LINE:COL", or the `--set` that wrote it),
  // for the SLAM settings' messages about its value.
  std::vector<std::string> settings_override_origins;
};

// scoring: how a run's estimates are judged against the simulator's truth (metrics only; no
// estimate changes with them). Written into metrics.json with the figures they define.
struct ScoringConfig {
  // A true slip event is one stance of one foot whose sole's net horizontal displacement while in
  // contact exceeds this (m): about 2.4x the normal floor's creep of 1.3 mm per stance, and above
  // what the encoders resolve (1.5 mrad at the 0.1 m leg: 0.15 mm).
  double slip_travel_m = 0.003;
  // A foot's simulated contact changes only after it has held the new state this long (s): a
  // sole that chatters on the ground for a step or two is one touch-down.
  double contact_debounce_s = 0.003;
  // A detection matches a true event of the same foot when its onset lies within
  // [start - before, end + after] of the event (s).
  double slip_match_before_s = 0.02;
  double slip_match_after_s = 0.04;
};

struct Scenario {
  std::string source_file;           // the YAML the scenario came from (absolute)
  std::string name;
  uint64_t seed = 0;
  double duration_s = 10;            // simulated time (s)
  double physics_dt_s = 0.001;       // physics.timestep_s (s)
  std::string world;                 // MJCF of the world (absolute after loading)
  RobotConfig robot;
  SensorsConfig sensors;
  std::vector<ObstacleConfig> obstacles;
  TerrainConfig terrain;
  std::vector<Disturbance> disturbances;
  SlamConfig slam;
  ScoringConfig scoring;
};

}  // namespace viqu

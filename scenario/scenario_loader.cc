#include "scenario/scenario_loader.h"

#include <filesystem>
#include <set>

#include "common/errors.h"
#include "common/yaml_emit.h"
#include "common/yaml_strict.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kGaitTypes = {"trot", "walk"};
const std::vector<std::string> kFollowModes = {"ground_truth", "estimate"};
const std::vector<std::string> kCategories = {"person", "box", "ball", "furniture"};
const std::vector<std::string> kLoopModes = {"none", "loop", "pingpong"};
const std::vector<std::string> kSlamModes = {"visual", "visual_dynamic", "full"};
const std::vector<std::string> kDynamicMethods = {"none", "semantic", "paper", "adaptive"};

// Names that end up in file and MuJoCo body names: letters, digits, '_', '-', '.'.
bool IsSafeName(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

void ReadSafeName(YamlMapReader* m, const std::string& key, std::string* out) {
  if (!m->String(key, out)) return;
  if (!IsSafeName(*out)) {
    m->source().Fail(m->KeyPath(key), m->Get(key),
                     "key '" + m->KeyPath(key) + "' expected a name of letters, digits, '_', '-' or '.', got '" +
                         *out + "'");
  }
}

// A path relative to the scenario file's folder, made absolute; the file must exist.
void ReadFilePath(YamlMapReader* m, const std::string& key, const fs::path& base_dir, std::string* out) {
  std::string text;
  if (!m->String(key, &text)) return;
  const fs::path resolved = (fs::path(text).is_absolute() ? fs::path(text) : base_dir / text).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(resolved, ec)) {
    m->source().Fail(m->KeyPath(key), m->Get(key),
                     "key '" + m->KeyPath(key) + "': file not found: " + resolved.string());
  }
  *out = resolved.string();
}

bool ReadVec2(YamlMapReader* m, const std::string& key, Vec2* out,
              const NumberRange& range = NumberRange::Any()) {
  std::vector<double> v;
  if (!m->NumberList(key, &v, 2, range)) return false;
  *out = {v[0], v[1]};
  return true;
}

// A list of [x, y] points.
std::vector<Vec2> ReadPointList(const YamlSource& src, const YAML::Node& list, const std::string& key_path) {
  std::vector<Vec2> points;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node& const_list = list;
    const std::vector<double> p =
        ReadYamlNumberList(src, const_list[i], JoinKeyPath(key_path, std::to_string(i)), 2);
    points.push_back({p[0], p[1]});
  }
  return points;
}

YAML::Node Element(const YAML::Node& list, size_t i) {
  const YAML::Node& const_list = list;
  return const_list[i];
}

void ReadGait(YamlMapReader m, GaitConfig* g) {
  m.Choice("type", &g->type, kGaitTypes);
  m.Number("frequency_hz", &g->frequency_hz, NumberRange::OpenClosed(0, 20));
  m.Number("duty", &g->duty, NumberRange::Open(0, 1));
  m.Number("step_height_m", &g->step_height_m, NumberRange::Closed(0, 0.1));
  m.RejectUnknownKeys();
}

void ReadCommand(YamlMapReader m, CommandConfig* c) {
  const YAML::Node waypoints = m.List("waypoints");
  c->waypoints = ReadPointList(m.source(), waypoints, m.KeyPath("waypoints"));
  m.Number("speed_mps", &c->speed_mps, NumberRange::OpenClosed(0, 5));
  m.Choice("follow", &c->follow, kFollowModes);
  m.Bool("loop", &c->loop);
  const YAML::Node velocity = m.List("velocity");
  c->velocity.clear();
  for (size_t i = 0; i < velocity.size(); ++i) {
    const YAML::Node item = Element(velocity, i);
    YamlMapReader e(m.source(), item, JoinKeyPath(m.KeyPath("velocity"), std::to_string(i)), item);
    VelocityCommand v;
    NumberRange t_range = NumberRange::NonNegative();
    if (!c->velocity.empty()) t_range = {c->velocity.back().t_s, t_range.hi, true, false};
    e.Require("t_s");
    e.Number("t_s", &v.t_s, t_range);
    e.Number("forward_mps", &v.forward_mps, NumberRange::Closed(-5, 5));
    e.Number("yaw_rate_dps", &v.yaw_rate_dps, NumberRange::Closed(-720, 720));
    e.RejectUnknownKeys();
    c->velocity.push_back(v);
  }
  if (!c->waypoints.empty() && !c->velocity.empty()) {
    m.source().Fail(m.KeyPath("velocity"), velocity,
                    "key '" + m.KeyPath("velocity") + "': give either waypoints or a velocity schedule, not both");
  }
  m.RejectUnknownKeys();
}

void ReadRobot(YamlMapReader m, const fs::path& base_dir, RobotConfig* r) {
  m.Require("model");
  ReadFilePath(&m, "model", base_dir, &r->model);
  const fs::path urdf = fs::path(r->model).replace_extension(".urdf");
  std::error_code ec;
  if (!fs::is_regular_file(urdf, ec)) {
    m.source().Fail(m.KeyPath("model"), m.Get("model"),
                    "key '" + m.KeyPath("model") + "': the robot's URDF is missing beside its MJCF: " +
                        urdf.string());
  }
  YamlMapReader start = m.Map("start");
  ReadVec2(&start, "xy", &r->start.xy);
  start.Number("yaw_deg", &r->start.yaw_deg, NumberRange::Closed(-360, 360));
  start.RejectUnknownKeys();
  ReadGait(m.Map("gait"), &r->gait);
  ReadCommand(m.Map("command"), &r->command);
  m.Bool("allow_fall", &r->allow_fall);
  m.RejectUnknownKeys();
}

void ReadSensors(YamlMapReader m, double physics_rate_hz, SensorsConfig* s) {
  const NumberRange rate = NumberRange::OpenClosed(0, physics_rate_hz);
  YamlMapReader cam = m.Map("camera");
  cam.Number("rate_hz", &s->camera.rate_hz, rate);
  cam.Integer("width", &s->camera.width, NumberRange::Closed(16, 4096));
  cam.Integer("height", &s->camera.height, NumberRange::Closed(16, 4096));
  // The side that limits the SLAM settings' image pyramid, where the user wrote it.
  const char* smaller = s->camera.height <= s->camera.width ? "height" : "width";
  const char* other = smaller[0] == 'h' ? "width" : "height";
  if (cam.Has(smaller)) {
    s->camera.size_where = cam.Where(smaller) + " (sensors.camera." + smaller + ")";
  } else if (cam.Has(other)) {
    s->camera.size_where = cam.Where(other) + " (sensors.camera." + other + ")";
  }
  // Up to 170 deg: beyond it MuJoCo's single-precision frustum no longer matches the pinhole
  // model (175 deg fails the renderer's check, 170 passes; measured).
  cam.Number("fovy_deg", &s->camera.fovy_deg, NumberRange::OpenClosed(0, 170));
  cam.Number("baseline_m", &s->camera.baseline_m, NumberRange::OpenClosed(0, 1));
  cam.Number("noise_std", &s->camera.noise_std, NumberRange::Closed(0, 255));
  cam.Bool("depth", &s->camera.depth);
  cam.Bool("segmentation", &s->camera.segmentation);
  if (cam.Has("dropouts")) {
    const YAML::Node list = cam.List("dropouts");
    s->camera.dropouts = ReadPointList(cam.source(), list, cam.KeyPath("dropouts"));
    for (size_t i = 0; i < s->camera.dropouts.size(); ++i) {
      const Vec2& d = s->camera.dropouts[i];
      if (!(d[0] >= 0 && d[1] > d[0])) {
        cam.source().Fail(JoinKeyPath(cam.KeyPath("dropouts"), std::to_string(i)), Element(list, i),
                          "a dropout is [t0_s, t1_s] with 0 <= t0_s < t1_s");
      }
    }
  }
  cam.RejectUnknownKeys();

  YamlMapReader imu = m.Map("imu");
  imu.Number("rate_hz", &s->imu.rate_hz, rate);
  imu.Number("accel_noise", &s->imu.accel_noise, NumberRange::NonNegative());
  imu.Number("gyro_noise", &s->imu.gyro_noise, NumberRange::NonNegative());
  imu.Number("accel_bias_walk", &s->imu.accel_bias_walk, NumberRange::NonNegative());
  imu.Number("gyro_bias_walk", &s->imu.gyro_bias_walk, NumberRange::NonNegative());
  imu.Choice("sampling", &s->imu.sampling, {"instant", "mean"});
  imu.RejectUnknownKeys();

  YamlMapReader joints = m.Map("joints");
  joints.Number("rate_hz", &s->joints.rate_hz, rate);
  joints.Number("noise_rad", &s->joints.noise_rad, NumberRange::NonNegative());
  joints.Number("resolution_rad", &s->joints.resolution_rad, NumberRange::Closed(0, 0.1));
  joints.Number("torque_noise_nm", &s->joints.torque_noise_nm, NumberRange::Closed(0, 10));
  const bool resolution_given =
      joints.Number("torque_resolution_nm", &s->joints.torque_resolution_nm, NumberRange::Closed(0, 1));
  // torque_quantum_nm: the same setting under the design's name (the run folder's contract names
  // it so); torque_resolution_nm is the encoder-style name (resolution_rad). One of them.
  double quantum = 0;
  if (joints.Number("torque_quantum_nm", &quantum, NumberRange::Closed(0, 1))) {
    if (resolution_given) {
      throw InputError(joints.Where("torque_quantum_nm") +
                       ": sensors.joints.torque_quantum_nm and torque_resolution_nm are one setting (the torque "
                       "reading's quantisation step, N m): give one of them");
    }
    s->joints.torque_resolution_nm = quantum;
  }
  joints.Number("torque_bias_nm", &s->joints.torque_bias_nm, NumberRange::Closed(0, 10));
  joints.Number("torque_delay_s", &s->joints.torque_delay_s, NumberRange::Closed(0, 1));
  joints.Choice("torque_sampling", &s->joints.torque_sampling, {"instant", "mean"});
  joints.RejectUnknownKeys();

  YamlMapReader touch = m.Map("touch");
  touch.Number("threshold_n", &s->touch.threshold_n, NumberRange::Positive());
  touch.Number("noise_n", &s->touch.noise_n, NumberRange::NonNegative());
  touch.RejectUnknownKeys();

  YamlMapReader seg = m.Map("segmentation");
  seg.Number("miss_rate", &s->segmentation.miss_rate, NumberRange::Closed(0, 1));
  seg.Integer("dilate_px", &s->segmentation.dilate_px, NumberRange::Closed(0, 50));
  seg.Integer("latency_frames", &s->segmentation.latency_frames, NumberRange::Closed(0, 100));
  // At most 100000 px, a third of a 640 x 480 image: beyond that nearly every object is dropped.
  seg.Integer("min_area_px", &s->segmentation.min_area_px, NumberRange::Closed(0, 100000));
  seg.Number("false_positive_rate", &s->segmentation.false_positive_rate, NumberRange::Closed(0, 1));
  seg.Number("wrong_category_rate", &s->segmentation.wrong_category_rate, NumberRange::Closed(0, 1));
  seg.Integer("boundary_jitter_px", &s->segmentation.boundary_jitter_px, NumberRange::Closed(0, 50));
  seg.RejectUnknownKeys();
  m.RejectUnknownKeys();
}

void ReadDisturbances(const YamlSource& src, const YAML::Node& list, const std::string& key_path,
                      std::vector<Disturbance>* out) {
  out->clear();
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = Element(list, i);
    YamlMapReader m(src, item, JoinKeyPath(key_path, std::to_string(i)), item);
    Disturbance d;
    m.Require("t_s");
    m.Number("t_s", &d.t_s, NumberRange::Closed(0, 24 * 3600));
    m.Require("force_n");
    std::vector<double> f;
    // At most 100 N: 20 times the robot's weight, beyond any push that the model survives.
    m.NumberList("force_n", &f, 3, NumberRange::Closed(-100, 100));
    d.force_n = {f[0], f[1], f[2]};
    m.Number("duration_s", &d.duration_s, NumberRange::OpenClosed(0, 60));
    m.RejectUnknownKeys();
    out->push_back(d);
  }
}

// Expected number of size_m entries per category.
size_t SizeEntries(const std::string& category) {
  return (category == "box" || category == "furniture") ? 3 : 1;
}

// The most obstacles a scenario may have. Measured on the 2-core machine: 1,000 people build and
// run (at 0.003x real time), 20,000 overflow MuJoCo 2.2's stack while the model is compiled.
constexpr size_t kMaxObstacles = 1000;
// The person mesh is scaled from a 1.72 m adult; outside this range (m) it is no person.
constexpr double kMinPersonHeightM = 0.5, kMaxPersonHeightM = 2.5;

void ReadObstacles(const YamlSource& src, const YAML::Node& list, const std::string& key_path,
                   std::vector<ObstacleConfig>* out) {
  out->clear();
  if (list.size() > kMaxObstacles) {
    src.Fail(key_path, list, "at most " + std::to_string(kMaxObstacles) + " obstacles, got " + std::to_string(list.size()));
  }
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = Element(list, i);
    YamlMapReader m(src, item, JoinKeyPath(key_path, std::to_string(i)), item);
    ObstacleConfig o;
    m.Require("name");
    ReadSafeName(&m, "name", &o.name);
    if (!names.insert(o.name).second) {
      src.Fail(m.KeyPath("name"), m.Get("name"), "obstacle name '" + o.name + "' is used twice");
    }
    m.Choice("category", &o.category, kCategories);
    m.NumberList("size_m", &o.size_m, SizeEntries(o.category), NumberRange::OpenClosed(0, 10));
    if (o.category == "person" && !o.size_m.empty() &&
        (o.size_m[0] < kMinPersonHeightM || o.size_m[0] > kMaxPersonHeightM)) {
      src.Fail(m.KeyPath("size_m"), m.Get("size_m"), "a person's height must be within [0.5, 2.5] m, got " + m.Get("size_m")[0].Scalar());
    }
    m.Require("path");
    o.path = ReadPointList(src, m.List("path"), m.KeyPath("path"));
    if (o.path.empty()) {
      src.Fail(m.KeyPath("path"), m.Get("path"),
               "key '" + m.KeyPath("path") + "' expected a list of at least one [x, y] point, got an empty list");
    }
    m.Number("speed_mps", &o.speed_mps, NumberRange::OpenClosed(0, 10));
    m.Number("start_s", &o.start_s, NumberRange::NonNegative());
    m.Number("pause_s", &o.pause_s, NumberRange::NonNegative());
    m.Choice("loop", &o.loop, kLoopModes);
    m.Number("yaw_deg", &o.yaw_deg, NumberRange::Closed(-360, 360));
    m.RejectUnknownKeys();
    out->push_back(o);
  }
}

void ReadTerrain(YamlMapReader m, TerrainConfig* t) {
  m.Number("friction", &t->friction, NumberRange::OpenClosed(0, 10));
  const YAML::Node patches = m.List("patches");
  t->patches.clear();
  for (size_t i = 0; i < patches.size(); ++i) {
    const YAML::Node item = Element(patches, i);
    YamlMapReader p(m.source(), item, JoinKeyPath(m.KeyPath("patches"), std::to_string(i)), item);
    FrictionPatch patch;
    p.Require("center");
    ReadVec2(&p, "center", &patch.center);
    ReadVec2(&p, "size", &patch.size, NumberRange::OpenClosed(0, 100));
    p.Number("friction", &patch.friction, NumberRange::OpenClosed(0, 10));
    p.RejectUnknownKeys();
    t->patches.push_back(patch);
  }
  const YAML::Node slopes = m.List("slopes");
  t->slopes.clear();
  for (size_t i = 0; i < slopes.size(); ++i) {
    const YAML::Node item = Element(slopes, i);
    YamlMapReader s(m.source(), item, JoinKeyPath(m.KeyPath("slopes"), std::to_string(i)), item);
    Slope slope;
    s.Require("center");
    ReadVec2(&s, "center", &slope.center);
    ReadVec2(&s, "size", &slope.size, NumberRange::OpenClosed(0, 100));
    // The terrain builder's own limits (sim/terrain.cc): steeper ramps are beyond the trot.
    s.Number("angle_deg", &slope.angle_deg, NumberRange::Closed(-30, 30));
    if (slope.angle_deg == 0) {
      throw InputError(s.Where("angle_deg") + ": key '" + s.KeyPath("angle_deg") +
                       "' must not be 0 (a flat ramp; leave the slope out)");
    }
    s.Number("yaw_deg", &slope.yaw_deg, NumberRange::Closed(-360, 360));
    s.RejectUnknownKeys();
    t->slopes.push_back(slope);
  }
  m.RejectUnknownKeys();
}

void ReadSlam(YamlMapReader m, const fs::path& base_dir, SlamConfig* s) {
  // Each present key becomes a SLAM settings override, with where it was read for messages.
  auto add = [s](std::string assignment, std::string origin) {
    s->settings_overrides.push_back(std::move(assignment));
    s->settings_override_origins.push_back(std::move(origin));
  };
  if (m.Choice("mode", &s->mode, kSlamModes)) add("mode=" + s->mode, m.Where("mode"));
  ReadFilePath(&m, "config", base_dir, &s->config);
  YamlMapReader d = m.Map("dynamic");
  // Present keys become overrides of the SLAM settings' `dynamic.*` (the settings file holds the
  // defaults for the rest).
  auto number = [&](const char* key, double* v, const NumberRange& range) {
    if (d.Number(key, v, range)) add(std::string("dynamic.") + key + "=" + YamlNumberText(*v), d.Where(key));
  };
  if (d.Choice("method", &s->dynamic.method, kDynamicMethods)) {
    add("dynamic.method=" + s->dynamic.method, d.Where("method"));
  }
  number("alpha", &s->dynamic.alpha, NumberRange::NonNegative());
  number("beta", &s->dynamic.beta, NumberRange::NonNegative());
  number("gamma", &s->dynamic.gamma, NumberRange::NonNegative());
  number("th_d", &s->dynamic.th_d, NumberRange::NonNegative());
  number("window_s", &s->dynamic.window_s, NumberRange::Positive());
  if (d.Integer("window_n", &s->dynamic.window_n, NumberRange::Closed(2, 10000))) {
    add("dynamic.window_n=" + std::to_string(s->dynamic.window_n), d.Where("window_n"));
  }
  // The rest of the block: as for slam.lo below, the keys and their kinds are checked here, each
  // value's range by the SLAM settings loader when the run starts.
  auto add_more = [&](const YamlMapReader& r, const std::string& prefix, const char* key, const std::string& value) {
    s->dynamic.more.emplace_back(prefix + key, value);
    add("dynamic." + prefix + key + "=" + value, r.Where(key));
  };
  auto more = [&](YamlMapReader* r, const std::string& prefix, std::initializer_list<const char*> keys) {
    for (const char* key : keys) {
      double v = 0;
      if (r->Number(key, &v, NumberRange::NonNegative())) add_more(*r, prefix, key, YamlNumberText(v));
    }
  };
  more(&d, "", {"forget_s"});
  bool keep_past = true;
  if (d.Bool("keep_past_observations", &keep_past)) {
    add_more(d, "", "keep_past_observations", keep_past ? "true" : "false");
  }
  YamlMapReader prior = d.Map("prior");
  more(&prior, "prior.", {"person", "box", "ball"});
  prior.RejectUnknownKeys();
  YamlMapReader adaptive = d.Map("adaptive");
  more(&adaptive, "adaptive.",
       {"lag_s", "threshold_m", "k_sigma", "disparity_sigma_px", "pixel_sigma_px", "max_speed_mps", "still_max_m",
        "hold_s", "stop_max_m", "foreground_band_m", "static_pose_min_share", "silhouette_threshold_m",
        "silhouette_lag_s", "silhouette_growth_px", "silhouette_behind_m"});
  for (const char* key : {"confirm_frames", "drop_frames", "min_matches", "interior_px", "max_hamming",
                          "changed_look_frames", "static_pose_outliers", "silhouette_min_rows"}) {
    int v = 0;
    if (adaptive.Integer(key, &v, NumberRange::NonNegative())) add_more(adaptive, "adaptive.", key, std::to_string(v));
  }
  adaptive.RejectUnknownKeys();
  d.RejectUnknownKeys();
  // slam.lo: the leg-odometry settings. The SLAM settings loader checks each value's range when
  // the run starts; here the keys and their kinds are checked, so that a misspelt key is an error
  // at its line.
  YamlMapReader lo = m.Map("lo");
  std::string contact;
  if (lo.Choice("contact", &contact, {"schedule", "touch", "estimated"})) {
    s->lo.emplace_back("contact", contact);
  }
  std::string imu_sampling;
  if (lo.Choice("imu_sampling", &imu_sampling, {"instant", "mean"})) s->lo.emplace_back("imu_sampling", imu_sampling);
  std::string slip_reference;
  if (lo.Choice("slip_reference", &slip_reference, {"position", "prediction"})) {
    s->lo.emplace_back("slip_reference", slip_reference);
  }
  bool hold_gravity = false;
  if (lo.Bool("fusion_hold_gravity", &hold_gravity)) {
    s->lo.emplace_back("fusion_hold_gravity", hold_gravity ? "true" : "false");
  }
  for (const char* key : {"attitude_gain", "gyro_bias_gain", "gravity_gate_mps2", "attitude_accel_average_s",
                          "accel_noise", "stance_foot_noise", "swing_foot_noise", "kin_position_noise_m",
                          "kin_velocity_noise_mps", "velocity_window_s", "touchdown_s", "touchdown_inflation",
                          "touchdown_inflation_vertical", "slip_gate_chi2", "slip_min_window_s", "slip_speed_mps", "slip_travel_m", "slip_travel_from_s",
                          "yaw_bias_initial_std", "yaw_bias_walk", "yaw_pair_noise_m", "yaw_pair_min_s",
                          "yaw_pair_max_s", "yaw_pair_max_rate_radps",
                          "yaw_pair_gate_chi2", "contact_height_m", "fusion_min_inliers", "fusion_gyro_bias_s",
                          "fusion_tilt_gate_deg", "fusion_tilt_carry_gate_deg", "fusion_tilt_window_s"}) {
    double v = 0;
    if (lo.Number(key, &v, NumberRange::NonNegative())) s->lo.emplace_back(key, YamlNumberText(v));
  }
  for (const auto& [key, value] : s->lo) add("lo." + key + "=" + value, lo.Where(key));
  lo.RejectUnknownKeys();
  // slam.stereo: the same checks as slam.lo (kinds here, ranges when the run starts).
  YamlMapReader stereo = m.Map("stereo");
  std::string subpixel;
  if (stereo.Choice("subpixel", &subpixel, {"parabola", "equiangular"})) s->stereo.emplace_back("subpixel", subpixel);
  for (const char* key : {"max_hamming", "row_band_px", "sad_half_window", "sad_search_px", "max_ratio", "min_depth_m",
                          "max_depth_baselines", "scale_factor", "sad_outlier_factor", "sad_uniqueness", "max_shear",
                          "shear_step", "lr_check_px", "near_mono_baselines", "near_right_weight_tracking",
                          "near_right_weight_ba"}) {
    double v = 0;
    if (stereo.Number(key, &v, NumberRange::NonNegative())) s->stereo.emplace_back(key, YamlNumberText(v));
  }
  for (const auto& [key, value] : s->stereo) add("stereo." + key + "=" + value, stereo.Where(key));
  stereo.RejectUnknownKeys();
  m.RejectUnknownKeys();
}

}  // namespace

Scenario LoadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  YamlSource src(path);
  YAML::Node root = LoadYamlFile(path);
  for (const std::string& o : overrides) ApplyYamlOverride(&root, o, &src);

  const fs::path abs_path = fs::absolute(path).lexically_normal();
  const fs::path base_dir = abs_path.parent_path();
  Scenario s;
  s.source_file = abs_path.string();

  YamlMapReader top(src, root, "");
  top.Require("name");
  ReadSafeName(&top, "name", &s.name);
  top.Unsigned("seed", &s.seed);
  top.Number("duration_s", &s.duration_s, NumberRange::OpenClosed(0, 24 * 3600));
  YamlMapReader physics = top.Map("physics");
  physics.Number("timestep_s", &s.physics_dt_s, NumberRange::OpenClosed(0, 0.01));
  physics.RejectUnknownKeys();
  top.Require("world");
  ReadFilePath(&top, "world", base_dir, &s.world);
  top.Require("robot");
  ReadRobot(top.Map("robot"), base_dir, &s.robot);
  ReadSensors(top.Map("sensors"), 1.0 / s.physics_dt_s, &s.sensors);
  ReadObstacles(src, top.List("obstacles"), "obstacles", &s.obstacles);
  ReadTerrain(top.Map("terrain"), &s.terrain);
  ReadDisturbances(src, top.List("disturbances"), "disturbances", &s.disturbances);
  ReadSlam(top.Map("slam"), base_dir, &s.slam);
  YamlMapReader scoring = top.Map("scoring");
  scoring.Number("slip_travel_m", &s.scoring.slip_travel_m, NumberRange::OpenClosed(0, 1));
  scoring.Number("contact_debounce_s", &s.scoring.contact_debounce_s, NumberRange::Closed(0, 0.1));
  scoring.Number("slip_match_before_s", &s.scoring.slip_match_before_s, NumberRange::Closed(0, 1));
  scoring.Number("slip_match_after_s", &s.scoring.slip_match_after_s, NumberRange::Closed(0, 1));
  scoring.RejectUnknownKeys();
  top.RejectUnknownKeys();
  return s;
}

}  // namespace viqu

#include <cstdio>
#include <cstdlib>
#include <string>

#include <yaml-cpp/yaml.h>

#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

// The shortest of %.15g / %.17g that reads back as the same double.
std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.15g", v);
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

void Str(YAML::Emitter& out, const std::string& key, const std::string& value) {
  out << YAML::Key << key << YAML::Value << YAML::DoubleQuoted << value;
}

// A value from a fixed set of plain words (trot, full, ...): no quotes needed.
void Word(YAML::Emitter& out, const std::string& key, const std::string& value) {
  out << YAML::Key << key << YAML::Value << value;
}

void Number(YAML::Emitter& out, const std::string& key, double value) {
  out << YAML::Key << key << YAML::Value << Num(value);
}

void Int(YAML::Emitter& out, const std::string& key, long long value) {
  out << YAML::Key << key << YAML::Value << std::to_string(value);
}

void Bool(YAML::Emitter& out, const std::string& key, bool value) {
  out << YAML::Key << key << YAML::Value << (value ? "true" : "false");
}

void Vec(YAML::Emitter& out, const Vec2& v) {
  out << YAML::Flow << YAML::BeginSeq << Num(v[0]) << Num(v[1]) << YAML::EndSeq;
}

void VecKey(YAML::Emitter& out, const std::string& key, const Vec2& v) {
  out << YAML::Key << key << YAML::Value;
  Vec(out, v);
}

void Points(YAML::Emitter& out, const std::string& key, const std::vector<Vec2>& points) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const Vec2& p : points) Vec(out, p);
  out << YAML::EndSeq;
}

void Robot(YAML::Emitter& out, const RobotConfig& r) {
  out << YAML::Key << "robot" << YAML::Value << YAML::BeginMap;
  Str(out, "model", r.model);
  out << YAML::Key << "start" << YAML::Value << YAML::Flow << YAML::BeginMap;
  VecKey(out, "xy", r.start.xy);
  Number(out, "yaw_deg", r.start.yaw_deg);
  out << YAML::EndMap;
  out << YAML::Key << "gait" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Word(out, "type", r.gait.type);
  Number(out, "frequency_hz", r.gait.frequency_hz);
  Number(out, "duty", r.gait.duty);
  Number(out, "step_height_m", r.gait.step_height_m);
  out << YAML::EndMap;
  out << YAML::Key << "command" << YAML::Value << YAML::BeginMap;
  Points(out, "waypoints", r.command.waypoints);
  Number(out, "speed_mps", r.command.speed_mps);
  Word(out, "follow", r.command.follow);
  Bool(out, "loop", r.command.loop);
  out << YAML::Key << "velocity" << YAML::Value;
  if (r.command.velocity.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const VelocityCommand& v : r.command.velocity) {
    out << YAML::Flow << YAML::BeginMap;
    Number(out, "t_s", v.t_s);
    Number(out, "forward_mps", v.forward_mps);
    Number(out, "yaw_rate_dps", v.yaw_rate_dps);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::EndMap;
  Bool(out, "allow_fall", r.allow_fall);
  out << YAML::EndMap;
}

void Sensors(YAML::Emitter& out, const SensorsConfig& s) {
  out << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "camera" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(out, "rate_hz", s.camera.rate_hz);
  Int(out, "width", s.camera.width);
  Int(out, "height", s.camera.height);
  Number(out, "fovy_deg", s.camera.fovy_deg);
  Number(out, "baseline_m", s.camera.baseline_m);
  Number(out, "noise_std", s.camera.noise_std);
  Bool(out, "depth", s.camera.depth);
  Bool(out, "segmentation", s.camera.segmentation);
  out << YAML::EndMap;
  out << YAML::Key << "imu" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(out, "rate_hz", s.imu.rate_hz);
  Number(out, "accel_noise", s.imu.accel_noise);
  Number(out, "gyro_noise", s.imu.gyro_noise);
  Number(out, "accel_bias_walk", s.imu.accel_bias_walk);
  Number(out, "gyro_bias_walk", s.imu.gyro_bias_walk);
  out << YAML::EndMap;
  out << YAML::Key << "joints" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(out, "rate_hz", s.joints.rate_hz);
  Number(out, "noise_rad", s.joints.noise_rad);
  Number(out, "resolution_rad", s.joints.resolution_rad);
  out << YAML::EndMap;
  out << YAML::Key << "segmentation" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(out, "miss_rate", s.segmentation.miss_rate);
  Int(out, "dilate_px", s.segmentation.dilate_px);
  Int(out, "latency_frames", s.segmentation.latency_frames);
  out << YAML::EndMap;
  out << YAML::EndMap;
}

void Obstacles(YAML::Emitter& out, const std::vector<ObstacleConfig>& obstacles) {
  out << YAML::Key << "obstacles" << YAML::Value;
  if (obstacles.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const ObstacleConfig& o : obstacles) {
    out << YAML::BeginMap;
    Str(out, "name", o.name);
    Word(out, "category", o.category);
    if (!o.size_m.empty()) {
      out << YAML::Key << "size_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (double x : o.size_m) out << Num(x);
      out << YAML::EndSeq;
    }
    Points(out, "path", o.path);
    Number(out, "speed_mps", o.speed_mps);
    Number(out, "start_s", o.start_s);
    Number(out, "pause_s", o.pause_s);
    Word(out, "loop", o.loop);
    Number(out, "yaw_deg", o.yaw_deg);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void Terrain(YAML::Emitter& out, const TerrainConfig& t) {
  out << YAML::Key << "terrain" << YAML::Value << YAML::BeginMap;
  Number(out, "friction", t.friction);
  out << YAML::Key << "patches" << YAML::Value;
  if (t.patches.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const FrictionPatch& p : t.patches) {
    out << YAML::Flow << YAML::BeginMap;
    VecKey(out, "center", p.center);
    VecKey(out, "size", p.size);
    Number(out, "friction", p.friction);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "slopes" << YAML::Value;
  if (t.slopes.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const Slope& s : t.slopes) {
    out << YAML::Flow << YAML::BeginMap;
    VecKey(out, "center", s.center);
    VecKey(out, "size", s.size);
    Number(out, "angle_deg", s.angle_deg);
    Number(out, "yaw_deg", s.yaw_deg);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::EndMap;
}

void Slam(YAML::Emitter& out, const SlamConfig& s) {
  out << YAML::Key << "slam" << YAML::Value << YAML::BeginMap;
  Word(out, "mode", s.mode);
  if (!s.config.empty()) Str(out, "config", s.config);
  out << YAML::Key << "dynamic" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Word(out, "method", s.dynamic.method);
  Number(out, "alpha", s.dynamic.alpha);
  Number(out, "beta", s.dynamic.beta);
  Number(out, "gamma", s.dynamic.gamma);
  Number(out, "th_d", s.dynamic.th_d);
  Number(out, "window_s", s.dynamic.window_s);
  Int(out, "window_n", s.dynamic.window_n);
  out << YAML::EndMap;
  out << YAML::EndMap;
}

}  // namespace

std::string ScenarioToYaml(const Scenario& s) {
  YAML::Emitter out;
  out << YAML::Comment("Fully resolved scenario (defaults filled in, --set applied, absolute paths).");
  out << YAML::Newline;
  out << YAML::BeginMap;
  Str(out, "name", s.name);
  out << YAML::Key << "seed" << YAML::Value << std::to_string(s.seed);
  Number(out, "duration_s", s.duration_s);
  out << YAML::Key << "physics" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(out, "timestep_s", s.physics_dt_s);
  out << YAML::EndMap;
  Str(out, "world", s.world);
  Robot(out, s.robot);
  Sensors(out, s.sensors);
  Obstacles(out, s.obstacles);
  Terrain(out, s.terrain);
  Slam(out, s.slam);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace viqu

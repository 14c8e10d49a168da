#include <string>

#include <yaml-cpp/yaml.h>

#include "common/yaml_emit.h"
#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

void Vec(YAML::Emitter& out, const Vec2& v) {
  out << YAML::Flow << YAML::BeginSeq << YamlNumberText(v[0]) << YamlNumberText(v[1]) << YAML::EndSeq;
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
  EmitString(out, "model", r.model);
  out << YAML::Key << "start" << YAML::Value << YAML::Flow << YAML::BeginMap;
  VecKey(out, "xy", r.start.xy);
  EmitNumber(out, "yaw_deg", r.start.yaw_deg);
  out << YAML::EndMap;
  out << YAML::Key << "gait" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitWord(out, "type", r.gait.type);
  EmitNumber(out, "frequency_hz", r.gait.frequency_hz);
  EmitNumber(out, "duty", r.gait.duty);
  EmitNumber(out, "step_height_m", r.gait.step_height_m);
  out << YAML::EndMap;
  out << YAML::Key << "command" << YAML::Value << YAML::BeginMap;
  Points(out, "waypoints", r.command.waypoints);
  EmitNumber(out, "speed_mps", r.command.speed_mps);
  EmitWord(out, "follow", r.command.follow);
  EmitBool(out, "loop", r.command.loop);
  out << YAML::Key << "velocity" << YAML::Value;
  if (r.command.velocity.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const VelocityCommand& v : r.command.velocity) {
    out << YAML::Flow << YAML::BeginMap;
    EmitNumber(out, "t_s", v.t_s);
    EmitNumber(out, "forward_mps", v.forward_mps);
    EmitNumber(out, "yaw_rate_dps", v.yaw_rate_dps);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::EndMap;
  EmitBool(out, "allow_fall", r.allow_fall);
  out << YAML::EndMap;
}

void Sensors(YAML::Emitter& out, const SensorsConfig& s) {
  out << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "camera" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "rate_hz", s.camera.rate_hz);
  EmitInt(out, "width", s.camera.width);
  EmitInt(out, "height", s.camera.height);
  EmitNumber(out, "fovy_deg", s.camera.fovy_deg);
  EmitNumber(out, "baseline_m", s.camera.baseline_m);
  EmitNumber(out, "noise_std", s.camera.noise_std);
  EmitBool(out, "depth", s.camera.depth);
  EmitBool(out, "segmentation", s.camera.segmentation);
  if (!s.camera.dropouts.empty()) Points(out, "dropouts", s.camera.dropouts);
  out << YAML::EndMap;
  out << YAML::Key << "imu" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "rate_hz", s.imu.rate_hz);
  EmitNumber(out, "accel_noise", s.imu.accel_noise);
  EmitNumber(out, "gyro_noise", s.imu.gyro_noise);
  EmitNumber(out, "accel_bias_walk", s.imu.accel_bias_walk);
  EmitNumber(out, "gyro_bias_walk", s.imu.gyro_bias_walk);
  out << YAML::Key << "sampling" << YAML::Value << s.imu.sampling;
  out << YAML::EndMap;
  out << YAML::Key << "joints" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "rate_hz", s.joints.rate_hz);
  EmitNumber(out, "noise_rad", s.joints.noise_rad);
  EmitNumber(out, "resolution_rad", s.joints.resolution_rad);
  EmitNumber(out, "torque_noise_nm", s.joints.torque_noise_nm);
  EmitNumber(out, "torque_resolution_nm", s.joints.torque_resolution_nm);
  EmitNumber(out, "torque_bias_nm", s.joints.torque_bias_nm);
  EmitNumber(out, "torque_delay_s", s.joints.torque_delay_s);
  out << YAML::Key << "torque_sampling" << YAML::Value << s.joints.torque_sampling;
  out << YAML::EndMap;
  out << YAML::Key << "touch" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "threshold_n", s.touch.threshold_n);
  EmitNumber(out, "noise_n", s.touch.noise_n);
  out << YAML::EndMap;
  out << YAML::Key << "segmentation" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "miss_rate", s.segmentation.miss_rate);
  EmitInt(out, "dilate_px", s.segmentation.dilate_px);
  EmitInt(out, "latency_frames", s.segmentation.latency_frames);
  EmitInt(out, "min_area_px", s.segmentation.min_area_px);
  EmitNumber(out, "false_positive_rate", s.segmentation.false_positive_rate);
  EmitNumber(out, "wrong_category_rate", s.segmentation.wrong_category_rate);
  EmitInt(out, "boundary_jitter_px", s.segmentation.boundary_jitter_px);
  out << YAML::EndMap;
  out << YAML::EndMap;
}

void Obstacles(YAML::Emitter& out, const std::vector<ObstacleConfig>& obstacles) {
  out << YAML::Key << "obstacles" << YAML::Value;
  if (obstacles.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const ObstacleConfig& o : obstacles) {
    out << YAML::BeginMap;
    EmitString(out, "name", o.name);
    EmitWord(out, "category", o.category);
    if (!o.size_m.empty()) {
      out << YAML::Key << "size_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (double x : o.size_m) out << YamlNumberText(x);
      out << YAML::EndSeq;
    }
    Points(out, "path", o.path);
    EmitNumber(out, "speed_mps", o.speed_mps);
    EmitNumber(out, "start_s", o.start_s);
    EmitNumber(out, "pause_s", o.pause_s);
    EmitWord(out, "loop", o.loop);
    EmitNumber(out, "yaw_deg", o.yaw_deg);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void Terrain(YAML::Emitter& out, const TerrainConfig& t) {
  out << YAML::Key << "terrain" << YAML::Value << YAML::BeginMap;
  EmitNumber(out, "friction", t.friction);
  out << YAML::Key << "patches" << YAML::Value;
  if (t.patches.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const FrictionPatch& p : t.patches) {
    out << YAML::Flow << YAML::BeginMap;
    VecKey(out, "center", p.center);
    VecKey(out, "size", p.size);
    EmitNumber(out, "friction", p.friction);
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
    EmitNumber(out, "angle_deg", s.angle_deg);
    EmitNumber(out, "yaw_deg", s.yaw_deg);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::EndMap;
}

void Slam(YAML::Emitter& out, const SlamConfig& s) {
  out << YAML::Key << "slam" << YAML::Value << YAML::BeginMap;
  EmitWord(out, "mode", s.mode);
  if (!s.config.empty()) EmitString(out, "config", s.config);
  out << YAML::Key << "dynamic" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitWord(out, "method", s.dynamic.method);
  EmitNumber(out, "alpha", s.dynamic.alpha);
  EmitNumber(out, "beta", s.dynamic.beta);
  EmitNumber(out, "gamma", s.dynamic.gamma);
  EmitNumber(out, "th_d", s.dynamic.th_d);
  EmitNumber(out, "window_s", s.dynamic.window_s);
  EmitInt(out, "window_n", s.dynamic.window_n);
  // The other keys present, nested as written (forget_s, prior.*, adaptive.*).
  for (const char* block : {"", "prior.", "adaptive."}) {
    const std::string prefix = block;
    bool open = false;
    for (const auto& [path, value] : s.dynamic.more) {
      if (path.rfind(prefix, 0) != 0 || (prefix.empty() && path.find('.') != std::string::npos)) continue;
      if (!prefix.empty() && !open) {
        out << YAML::Key << prefix.substr(0, prefix.size() - 1) << YAML::Value << YAML::BeginMap;
        open = true;
      }
      out << YAML::Key << path.substr(prefix.size()) << YAML::Value << value;
    }
    if (open) out << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!s.lo.empty()) {
    out << YAML::Key << "lo" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const auto& [key, value] : s.lo) out << YAML::Key << key << YAML::Value << value;
    out << YAML::EndMap;
  }
  if (!s.stereo.empty()) {
    out << YAML::Key << "stereo" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const auto& [key, value] : s.stereo) out << YAML::Key << key << YAML::Value << value;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

std::string ScenarioToYaml(const Scenario& s) {
  YAML::Emitter out;
  out << YAML::Comment("Fully resolved scenario (defaults filled in, --set applied, absolute paths).");
  out << YAML::Newline;
  out << YAML::BeginMap;
  EmitString(out, "name", s.name);
  out << YAML::Key << "seed" << YAML::Value << std::to_string(s.seed);
  EmitNumber(out, "duration_s", s.duration_s);
  out << YAML::Key << "physics" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "timestep_s", s.physics_dt_s);
  out << YAML::EndMap;
  EmitString(out, "world", s.world);
  Robot(out, s.robot);
  Sensors(out, s.sensors);
  Obstacles(out, s.obstacles);
  Terrain(out, s.terrain);
  if (!s.disturbances.empty()) {
    out << YAML::Key << "disturbances" << YAML::Value << YAML::BeginSeq;
    for (const Disturbance& d : s.disturbances) {
      out << YAML::Flow << YAML::BeginMap;
      EmitNumber(out, "t_s", d.t_s);
      out << YAML::Key << "force_n" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (double f : d.force_n) out << YamlNumberText(f);
      out << YAML::EndSeq;
      EmitNumber(out, "duration_s", d.duration_s);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  Slam(out, s.slam);
  out << YAML::Key << "scoring" << YAML::Value << YAML::Flow << YAML::BeginMap;
  EmitNumber(out, "slip_travel_m", s.scoring.slip_travel_m);
  EmitNumber(out, "contact_debounce_s", s.scoring.contact_debounce_s);
  EmitNumber(out, "slip_match_before_s", s.scoring.slip_match_before_s);
  EmitNumber(out, "slip_match_after_s", s.scoring.slip_match_after_s);
  out << YAML::EndMap;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace viqu

#include "slam/settings/slam_settings.h"

#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "common/yaml_emit.h"
#include "common/yaml_strict.h"

namespace viqu::slam {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kInputs = {"stereo", "rgbd"};
const std::vector<std::string> kMappingModes = {"sync", "realtime"};
const std::vector<std::string> kModes = {"visual", "visual_dynamic", "full"};
const std::vector<std::string> kDynamicMethods = {"none", "semantic", "paper", "adaptive"};
const std::vector<std::string> kContactSources = {"schedule", "touch", "estimated"};

// Ranges shared by several keys.
const NumberRange kRatio = NumberRange::OpenClosed(0, 1);        // a share or a ratio test, (0, 1]
const NumberRange kHamming = NumberRange::Closed(1, 256);        // ORB descriptors have 256 bits
const NumberRange kPyramidScale = NumberRange::OpenClosed(1, 4); // between pyramid levels
const NumberRange kGrey = NumberRange::Closed(1, 255);           // FAST thresholds (grey levels)
// Counts (features, keyframes, frames, iterations) get a finite upper bound: an integer range
// without one reads "an integer in [1, 2.14748e+09]" in messages.
constexpr double kMaxCount = 100000;
const NumberRange kCount0 = NumberRange::Closed(0, kMaxCount);
const NumberRange kCount1 = NumberRange::Closed(1, kMaxCount);
const NumberRange kCount3 = NumberRange::Closed(3, kMaxCount);  // a pose needs at least 3 points

// Fails at `a_key` of `a` when it is in the file (or came from --set), otherwise at `b_key` of
// `b`; with neither present the message names the file alone.
[[noreturn]] void FailAtEither(YamlMapReader* a, const std::string& a_key, YamlMapReader* b,
                               const std::string& b_key, const std::string& message) {
  const bool at_a = a->Has(a_key) || !b->Has(b_key);  // a and b may be the same map
  YamlMapReader* m = at_a ? a : b;
  const std::string& key = at_a ? a_key : b_key;
  m->source().Fail(m->KeyPath(key), m->Get(key), message);
}

void ReadOrb(YamlMapReader* m, OrbExtractorOptions* o) {
  m->Integer("num_features", &o->num_features, kCount1);
  m->Number("scale_factor", &o->scale_factor, kPyramidScale);
  m->Integer("num_levels", &o->num_levels, NumberRange::Closed(1, 32));
  m->Integer("fast_threshold", &o->fast_threshold, kGrey);
  m->Integer("fast_threshold_min", &o->fast_threshold_min, kGrey);
  m->Integer("cell_px", &o->cell_px, NumberRange::Closed(8, 4096));
  m->Bool("level_pixel_centres", &o->level_pixel_centres);
  m->RejectUnknownKeys();
  if (o->fast_threshold_min > o->fast_threshold) {
    FailAtEither(m, "fast_threshold_min", m, "fast_threshold",
                 "key '" + m->KeyPath("fast_threshold_min") + "' (" + std::to_string(o->fast_threshold_min) +
                     ") must not exceed '" + m->KeyPath("fast_threshold") + "' (" +
                     std::to_string(o->fast_threshold) + "): it is the retry threshold for cells that found nothing");
  }
}

void ReadStereo(YamlMapReader* m, StereoMatcherOptions* s) {
  m->Integer("max_hamming", &s->max_hamming, kHamming);
  m->Number("row_band_px", &s->row_band_px, NumberRange::Closed(0, 100));
  m->Integer("sad_half_window", &s->sad_half_window, NumberRange::Closed(1, 50));
  m->Integer("sad_search_px", &s->sad_search_px, NumberRange::Closed(0, 200));
  m->Number("max_ratio", &s->max_ratio, kRatio);
  m->Number("min_depth_m", &s->min_depth_m, NumberRange::Positive());
  m->Number("max_depth_baselines", &s->max_depth_baselines, NumberRange::Positive());
  m->Number("scale_factor", &s->scale_factor, kPyramidScale);
  m->Number("sad_outlier_factor", &s->sad_outlier_factor, NumberRange::AtLeast(1));
  m->Number("sad_uniqueness", &s->sad_uniqueness, kRatio);
  m->Choice("subpixel", &s->subpixel, {"parabola", "equiangular"});
  m->Number("max_shear", &s->max_shear, NumberRange::Closed(0, 2));
  m->Number("shear_step", &s->shear_step, NumberRange::OpenClosed(0, 2));
  m->Number("lr_check_px", &s->lr_check_px, NumberRange::Closed(0, 10));
  m->Number("near_mono_baselines", &s->near_mono_baselines, NumberRange::Closed(0, 1000));
  m->Number("near_right_weight_tracking", &s->near_right_weight_tracking, NumberRange::Closed(0, 1));
  m->Number("near_right_weight_ba", &s->near_right_weight_ba, NumberRange::Closed(0, 1));
  m->RejectUnknownKeys();
}

void ReadTracking(YamlMapReader* m, TrackingSettings* t) {
  m->Number("motion_search_px", &t->motion_search_px, NumberRange::OpenClosed(0, 1000));
  m->Number("local_map_search_px", &t->local_map_search_px, NumberRange::OpenClosed(0, 1000));
  m->Integer("max_hamming", &t->max_hamming, kHamming);
  m->Number("match_ratio", &t->match_ratio, kRatio);
  m->Integer("min_inliers", &t->min_inliers, kCount3);
  m->Integer("min_inliers_motion", &t->min_inliers_motion, kCount3);
  m->Integer("local_keyframes", &t->local_keyframes, kCount1);
  m->Integer("spatial_keyframes", &t->spatial_keyframes, kCount0);
  m->Number("spatial_radius_m", &t->spatial_radius_m, NumberRange::OpenClosed(0, 1000));
  m->Number("spatial_max_angle_deg", &t->spatial_max_angle_deg, NumberRange::OpenClosed(0, 180));
  m->Number("huber_px", &t->huber_px, NumberRange::Positive());
  m->Integer("pose_iterations", &t->pose_iterations, NumberRange::Closed(1, 100));
  m->Integer("keyframe_max_frames", &t->keyframe_max_frames, kCount1);
  m->Integer("keyframe_min_frames", &t->keyframe_min_frames, kCount0);
  m->Number("keyframe_ratio", &t->keyframe_ratio, kRatio);
  m->Integer("close_points_min", &t->close_points_min, kCount0);
  m->Integer("relocalise_min_inliers", &t->relocalise_min_inliers, NumberRange::Closed(4, kMaxCount));
  m->Integer("close_tracked_max", &t->close_tracked_max, kCount0);
  m->Integer("relocalise_ransac_min_inliers", &t->relocalise_ransac_min_inliers, NumberRange::Closed(4, kMaxCount));
  m->Integer("init_min_points", &t->init_min_points, kCount3);
  m->Integer("keyframe_new_points", &t->keyframe_new_points, kCount0);
  m->Integer("keyframe_min_inliers", &t->keyframe_min_inliers, kCount0);
  m->Integer("reinitialise_after_lost", &t->reinitialise_after_lost, kCount1);
  m->Integer("lost_carry_min_inliers", &t->lost_carry_min_inliers, kCount0);
  m->Number("weak_inliers_factor", &t->weak_inliers_factor, NumberRange::Closed(0, 100));
  m->Integer("relocalised_frames", &t->relocalised_frames, kCount0);
  m->Integer("relocalised_min_inliers", &t->relocalised_min_inliers, kCount3);
  m->Number("prior_window_factor", &t->prior_window_factor, NumberRange::OpenClosed(0, 100));
  m->Integer("prior_window_frames", &t->prior_window_frames, kCount1);
  m->Number("prior_window_min_px", &t->prior_window_min_px, NumberRange::OpenClosed(0, 1000));
  m->RejectUnknownKeys();
  if (t->keyframe_min_frames > t->keyframe_max_frames) {
    FailAtEither(m, "keyframe_min_frames", m, "keyframe_max_frames",
                 "key '" + m->KeyPath("keyframe_min_frames") + "' (" + std::to_string(t->keyframe_min_frames) +
                     ") must not exceed '" + m->KeyPath("keyframe_max_frames") + "' (" +
                     std::to_string(t->keyframe_max_frames) + ")");
  }
}

void ReadMapping(YamlMapReader* m, MappingSettings* p) {
  m->Choice("mode", &p->mode, kMappingModes);
  m->Integer("ba_window", &p->ba_window, kCount1);
  m->Integer("ba_iterations", &p->ba_iterations, NumberRange::Closed(1, 1000));
  m->Number("ba_huber_px", &p->ba_huber_px, NumberRange::Positive());
  m->Integer("covisibility_min", &p->covisibility_min, kCount1);
  m->Integer("triangulation_neighbours", &p->triangulation_neighbours, kCount1);
  m->Number("min_parallax_deg", &p->min_parallax_deg, NumberRange::ClosedOpen(0, 90));
  // 0 turns culling off, hence a closed interval.
  m->Number("culling_found_ratio", &p->culling_found_ratio, NumberRange::Closed(0, 1));
  m->Number("redundant_keyframe_ratio", &p->redundant_keyframe_ratio, kRatio);
  m->RejectUnknownKeys();
}

void ReadDynamic(YamlMapReader* m, DynamicSettings* d) {
  m->Choice("method", &d->method, kDynamicMethods);
  m->Number("alpha", &d->alpha, NumberRange::NonNegative());
  m->Number("beta", &d->beta, NumberRange::NonNegative());
  m->Number("gamma", &d->gamma, NumberRange::NonNegative());
  m->Number("th_d", &d->th_d, NumberRange::NonNegative());
  m->Number("window_s", &d->window_s, NumberRange::OpenClosed(0, 600));
  m->Integer("window_n", &d->window_n, NumberRange::Closed(2, 10000));
  m->Number("forget_s", &d->forget_s, NumberRange::OpenClosed(0, 600));
  m->Bool("keep_past_observations", &d->keep_past_observations);
  YamlMapReader prior = m->Map("prior");
  prior.Number("person", &d->prior.person, NumberRange::Closed(0, 1));
  prior.Number("box", &d->prior.box, NumberRange::Closed(0, 1));
  prior.Number("ball", &d->prior.ball, NumberRange::Closed(0, 1));
  prior.RejectUnknownKeys();
  YamlMapReader a = m->Map("adaptive");
  AdaptiveDynamicSettings* ad = &d->adaptive;
  a.Number("lag_s", &ad->lag_s, NumberRange::OpenClosed(0, 60));
  a.Number("threshold_m", &ad->threshold_m, NumberRange::NonNegative());
  a.Number("k_sigma", &ad->k_sigma, NumberRange::Closed(0, 100));
  a.Number("disparity_sigma_px", &ad->disparity_sigma_px, NumberRange::Closed(0, 100));
  a.Number("pixel_sigma_px", &ad->pixel_sigma_px, NumberRange::Closed(0, 100));
  a.Number("max_speed_mps", &ad->max_speed_mps, NumberRange::Positive());
  a.Number("still_max_m", &ad->still_max_m, NumberRange::Positive());
  a.Number("hold_s", &ad->hold_s, NumberRange::Closed(0, 600));
  a.Integer("confirm_frames", &ad->confirm_frames, NumberRange::Closed(1, 1000));
  a.Integer("drop_frames", &ad->drop_frames, NumberRange::Closed(1, 1000));
  a.Integer("min_matches", &ad->min_matches, kCount1);
  a.Integer("interior_px", &ad->interior_px, NumberRange::Closed(0, 100));
  a.Number("foreground_band_m", &ad->foreground_band_m, NumberRange::Positive());
  a.Integer("max_hamming", &ad->max_hamming, kHamming);
  a.Number("static_pose_min_share", &ad->static_pose_min_share, NumberRange::Closed(0, 1));
  a.Integer("static_pose_outliers", &ad->static_pose_outliers, NumberRange::Closed(0, 1));
  a.Number("stop_max_m", &ad->stop_max_m, NumberRange::NonNegative());
  a.Integer("changed_look_frames", &ad->changed_look_frames, NumberRange::Closed(0, 1000));
  a.Number("silhouette_threshold_m", &ad->silhouette_threshold_m, NumberRange::NonNegative());
  a.Number("silhouette_lag_s", &ad->silhouette_lag_s, NumberRange::OpenClosed(0, 60));
  a.Integer("silhouette_min_rows", &ad->silhouette_min_rows, kCount1);
  a.Number("silhouette_growth_px", &ad->silhouette_growth_px, NumberRange::Closed(0, 100));
  a.Number("silhouette_behind_m", &ad->silhouette_behind_m, NumberRange::NonNegative());
  a.RejectUnknownKeys();
  m->RejectUnknownKeys();
}

void ReadLegOdometry(YamlMapReader* m, LegOdometrySettings* lo) {
  m->Choice("contact", &lo->contact, kContactSources);
  m->Choice("imu_sampling", &lo->imu_sampling, {"instant", "mean"});
  m->Choice("slip_reference", &lo->slip_reference, {"position", "prediction"});
  m->Number("attitude_gain", &lo->attitude_gain, NumberRange::Closed(0, 100));
  m->Number("gyro_bias_gain", &lo->gyro_bias_gain, NumberRange::Closed(0, 100));
  m->Number("gravity_gate_mps2", &lo->gravity_gate_mps2, NumberRange::Positive());
  m->Number("attitude_accel_average_s", &lo->attitude_accel_average_s, NumberRange::Closed(0, 10));
  m->Number("accel_noise", &lo->accel_noise, NumberRange::Positive());
  m->Number("stance_foot_noise", &lo->stance_foot_noise, NumberRange::Positive());
  m->Number("swing_foot_noise", &lo->swing_foot_noise, NumberRange::Positive());
  m->Number("kin_position_noise_m", &lo->kin_position_noise_m, NumberRange::Positive());
  m->Number("kin_velocity_noise_mps", &lo->kin_velocity_noise_mps, NumberRange::Positive());
  m->Number("velocity_window_s", &lo->velocity_window_s, NumberRange::Closed(0, 1));
  m->Number("touchdown_s", &lo->touchdown_s, NumberRange::Closed(0, 10));
  m->Number("touchdown_inflation", &lo->touchdown_inflation, NumberRange::Closed(1, 1e6));
  m->Number("touchdown_inflation_vertical", &lo->touchdown_inflation_vertical, NumberRange::Closed(1, 1e6));
  m->Number("slip_gate_chi2", &lo->slip_gate_chi2, NumberRange::Positive());
  m->Number("slip_min_window_s", &lo->slip_min_window_s, NumberRange::Closed(0, 1));
  m->Number("contact_height_m", &lo->contact_height_m, NumberRange::Positive());
  m->Integer("fusion_min_inliers", &lo->fusion_min_inliers, kCount0);
  m->Number("fusion_tilt_gate_deg", &lo->fusion_tilt_gate_deg, NumberRange::Closed(0, 90));
  m->Number("fusion_tilt_carry_gate_deg", &lo->fusion_tilt_carry_gate_deg, NumberRange::Closed(0, 90));
  m->Number("fusion_tilt_window_s", &lo->fusion_tilt_window_s, NumberRange::OpenClosed(0, 60));
  m->Bool("fusion_hold_gravity", &lo->fusion_hold_gravity);
  m->Number("fusion_gyro_bias_s", &lo->fusion_gyro_bias_s, NumberRange::Closed(0, 1e6));
  m->Number("slip_speed_mps", &lo->slip_speed_mps, NumberRange::Positive());
  m->Number("slip_travel_m", &lo->slip_travel_m, NumberRange::Positive());
  m->Number("slip_travel_from_s", &lo->slip_travel_from_s, NumberRange::NonNegative());
  m->Number("yaw_bias_initial_std", &lo->yaw_bias_initial_std, NumberRange::NonNegative());
  m->Number("yaw_bias_walk", &lo->yaw_bias_walk, NumberRange::NonNegative());
  m->Number("yaw_pair_noise_m", &lo->yaw_pair_noise_m, NumberRange::Positive());
  m->Number("yaw_pair_min_s", &lo->yaw_pair_min_s, NumberRange::Positive());
  m->Number("yaw_pair_max_s", &lo->yaw_pair_max_s, NumberRange::Positive());
  m->Number("yaw_pair_max_rate_radps", &lo->yaw_pair_max_rate_radps, NumberRange::Positive());
  m->Number("yaw_pair_gate_chi2", &lo->yaw_pair_gate_chi2, NumberRange::Positive());
  m->RejectUnknownKeys();
}

}  // namespace

SlamSettings LoadSlamSettings(const std::string& path, const std::vector<std::string>& overrides,
                              const std::vector<std::string>& origins) {
  YamlSource src(path);
  YAML::Node root = LoadYamlFile(path);
  for (size_t i = 0; i < overrides.size(); ++i) {
    ApplyYamlOverride(&root, overrides[i], &src, i < origins.size() ? origins[i] : std::string());
  }

  SlamSettings s;
  s.source_file = fs::absolute(path).lexically_normal().string();

  YamlMapReader top(src, root, "");
  top.Choice("mode", &s.mode, kModes);
  top.Choice("input", &s.input, kInputs);
  top.Number("rgbd_max_depth_m", &s.rgbd_max_depth_m, NumberRange::Positive());
  top.Number("rgbd_virtual_baseline_m", &s.rgbd_virtual_baseline_m, NumberRange::OpenClosed(0, 10));
  YamlMapReader orb = top.Map("orb");
  ReadOrb(&orb, &s.orb);
  {
    const char* key = orb.Has("num_levels") || !orb.Has("scale_factor") ? "num_levels" : "scale_factor";
    s.pyramid_where = orb.Has(key) ? src.Where(orb.KeyPath(key), orb.Get(key)) : path;
  }
  YamlMapReader stereo = top.Map("stereo");
  ReadStereo(&stereo, &s.stereo);
  s.stereo.level_pixel_centres = s.orb.level_pixel_centres;  // one pyramid, one mapping
  YamlMapReader tracking = top.Map("tracking");
  ReadTracking(&tracking, &s.tracking);
  YamlMapReader mapping = top.Map("mapping");
  ReadMapping(&mapping, &s.mapping);
  YamlMapReader dynamic = top.Map("dynamic");
  ReadDynamic(&dynamic, &s.dynamic);
  YamlMapReader lo = top.Map("lo");
  ReadLegOdometry(&lo, &s.lo);
  top.RejectUnknownKeys();

  // The matcher searches right keypoints at the extractor's pyramid levels: the scales must agree.
  if (s.stereo.scale_factor != s.orb.scale_factor) {
    FailAtEither(&stereo, "scale_factor", &orb, "scale_factor",
                 "key 'stereo.scale_factor' (" + YamlNumberText(s.stereo.scale_factor) + ") must equal 'orb.scale_factor' (" +
                     YamlNumberText(s.orb.scale_factor) + "): the stereo matcher works on the extractor's pyramid; set both");
  }
  return s;
}

std::string DefaultSlamSettingsPath() { return VIQU_SOURCE_DIR "/slam/config/default.yaml"; }

std::string SlamSettingsToYaml(const SlamSettings& s) {
  YAML::Emitter out;
  std::string header = "Resolved SLAM settings (defaults filled in, --set applied)";
  if (!s.source_file.empty()) header += "; read from " + s.source_file;
  out << YAML::Comment(header) << YAML::Newline;
  out << YAML::BeginMap;
  EmitWord(out, "mode", s.mode);
  EmitWord(out, "input", s.input);
  EmitNumber(out, "rgbd_max_depth_m", s.rgbd_max_depth_m);
  EmitNumber(out, "rgbd_virtual_baseline_m", s.rgbd_virtual_baseline_m);

  out << YAML::Key << "orb" << YAML::Value << YAML::BeginMap;
  EmitInt(out, "num_features", s.orb.num_features);
  EmitNumber(out, "scale_factor", s.orb.scale_factor);
  EmitInt(out, "num_levels", s.orb.num_levels);
  EmitInt(out, "fast_threshold", s.orb.fast_threshold);
  EmitInt(out, "fast_threshold_min", s.orb.fast_threshold_min);
  EmitInt(out, "cell_px", s.orb.cell_px);
  EmitBool(out, "level_pixel_centres", s.orb.level_pixel_centres);
  out << YAML::EndMap;

  out << YAML::Key << "stereo" << YAML::Value << YAML::BeginMap;
  EmitInt(out, "max_hamming", s.stereo.max_hamming);
  EmitNumber(out, "row_band_px", s.stereo.row_band_px);
  EmitInt(out, "sad_half_window", s.stereo.sad_half_window);
  EmitInt(out, "sad_search_px", s.stereo.sad_search_px);
  EmitNumber(out, "max_ratio", s.stereo.max_ratio);
  EmitNumber(out, "min_depth_m", s.stereo.min_depth_m);
  EmitNumber(out, "max_depth_baselines", s.stereo.max_depth_baselines);
  EmitNumber(out, "scale_factor", s.stereo.scale_factor);
  EmitNumber(out, "sad_outlier_factor", s.stereo.sad_outlier_factor);
  EmitNumber(out, "sad_uniqueness", s.stereo.sad_uniqueness);
  EmitWord(out, "subpixel", s.stereo.subpixel);
  EmitNumber(out, "max_shear", s.stereo.max_shear);
  EmitNumber(out, "shear_step", s.stereo.shear_step);
  EmitNumber(out, "lr_check_px", s.stereo.lr_check_px);
  EmitNumber(out, "near_mono_baselines", s.stereo.near_mono_baselines);
  EmitNumber(out, "near_right_weight_tracking", s.stereo.near_right_weight_tracking);
  EmitNumber(out, "near_right_weight_ba", s.stereo.near_right_weight_ba);
  out << YAML::EndMap;

  const TrackingSettings& t = s.tracking;
  out << YAML::Key << "tracking" << YAML::Value << YAML::BeginMap;
  EmitNumber(out, "motion_search_px", t.motion_search_px);
  EmitNumber(out, "local_map_search_px", t.local_map_search_px);
  EmitInt(out, "max_hamming", t.max_hamming);
  EmitNumber(out, "match_ratio", t.match_ratio);
  EmitInt(out, "min_inliers", t.min_inliers);
  EmitInt(out, "min_inliers_motion", t.min_inliers_motion);
  EmitInt(out, "local_keyframes", t.local_keyframes);
  EmitInt(out, "spatial_keyframes", t.spatial_keyframes);
  EmitNumber(out, "spatial_radius_m", t.spatial_radius_m);
  EmitNumber(out, "spatial_max_angle_deg", t.spatial_max_angle_deg);
  EmitNumber(out, "huber_px", t.huber_px);
  EmitInt(out, "pose_iterations", t.pose_iterations);
  EmitInt(out, "keyframe_max_frames", t.keyframe_max_frames);
  EmitInt(out, "keyframe_min_frames", t.keyframe_min_frames);
  EmitNumber(out, "keyframe_ratio", t.keyframe_ratio);
  EmitInt(out, "close_points_min", t.close_points_min);
  EmitInt(out, "relocalise_min_inliers", t.relocalise_min_inliers);
  EmitInt(out, "close_tracked_max", t.close_tracked_max);
  EmitInt(out, "relocalise_ransac_min_inliers", t.relocalise_ransac_min_inliers);
  EmitInt(out, "init_min_points", t.init_min_points);
  EmitInt(out, "keyframe_new_points", t.keyframe_new_points);
  EmitInt(out, "keyframe_min_inliers", t.keyframe_min_inliers);
  EmitInt(out, "reinitialise_after_lost", t.reinitialise_after_lost);
  EmitInt(out, "lost_carry_min_inliers", t.lost_carry_min_inliers);
  EmitNumber(out, "weak_inliers_factor", t.weak_inliers_factor);
  EmitInt(out, "relocalised_frames", t.relocalised_frames);
  EmitInt(out, "relocalised_min_inliers", t.relocalised_min_inliers);
  EmitNumber(out, "prior_window_factor", t.prior_window_factor);
  EmitInt(out, "prior_window_frames", t.prior_window_frames);
  EmitNumber(out, "prior_window_min_px", t.prior_window_min_px);
  out << YAML::EndMap;

  const MappingSettings& m = s.mapping;
  out << YAML::Key << "mapping" << YAML::Value << YAML::BeginMap;
  EmitWord(out, "mode", m.mode);
  EmitInt(out, "ba_window", m.ba_window);
  EmitInt(out, "ba_iterations", m.ba_iterations);
  EmitNumber(out, "ba_huber_px", m.ba_huber_px);
  EmitInt(out, "covisibility_min", m.covisibility_min);
  EmitInt(out, "triangulation_neighbours", m.triangulation_neighbours);
  EmitNumber(out, "min_parallax_deg", m.min_parallax_deg);
  EmitNumber(out, "culling_found_ratio", m.culling_found_ratio);
  EmitNumber(out, "redundant_keyframe_ratio", m.redundant_keyframe_ratio);
  out << YAML::EndMap;

  const DynamicSettings& d = s.dynamic;
  out << YAML::Key << "dynamic" << YAML::Value << YAML::BeginMap;
  EmitWord(out, "method", d.method);
  EmitNumber(out, "alpha", d.alpha);
  EmitNumber(out, "beta", d.beta);
  EmitNumber(out, "gamma", d.gamma);
  EmitNumber(out, "th_d", d.th_d);
  EmitNumber(out, "window_s", d.window_s);
  EmitInt(out, "window_n", d.window_n);
  EmitNumber(out, "forget_s", d.forget_s);
  EmitBool(out, "keep_past_observations", d.keep_past_observations);
  out << YAML::Key << "prior" << YAML::Value << YAML::BeginMap;
  EmitNumber(out, "person", d.prior.person);
  EmitNumber(out, "box", d.prior.box);
  EmitNumber(out, "ball", d.prior.ball);
  out << YAML::EndMap;
  const AdaptiveDynamicSettings& a = d.adaptive;
  out << YAML::Key << "adaptive" << YAML::Value << YAML::BeginMap;
  EmitNumber(out, "lag_s", a.lag_s);
  EmitNumber(out, "threshold_m", a.threshold_m);
  EmitNumber(out, "k_sigma", a.k_sigma);
  EmitNumber(out, "disparity_sigma_px", a.disparity_sigma_px);
  EmitNumber(out, "pixel_sigma_px", a.pixel_sigma_px);
  EmitNumber(out, "max_speed_mps", a.max_speed_mps);
  EmitNumber(out, "still_max_m", a.still_max_m);
  EmitNumber(out, "hold_s", a.hold_s);
  EmitInt(out, "confirm_frames", a.confirm_frames);
  EmitInt(out, "drop_frames", a.drop_frames);
  EmitInt(out, "min_matches", a.min_matches);
  EmitInt(out, "interior_px", a.interior_px);
  EmitNumber(out, "foreground_band_m", a.foreground_band_m);
  EmitInt(out, "max_hamming", a.max_hamming);
  EmitNumber(out, "static_pose_min_share", a.static_pose_min_share);
  EmitInt(out, "static_pose_outliers", a.static_pose_outliers);
  EmitNumber(out, "stop_max_m", a.stop_max_m);
  EmitInt(out, "changed_look_frames", a.changed_look_frames);
  EmitNumber(out, "silhouette_threshold_m", a.silhouette_threshold_m);
  EmitNumber(out, "silhouette_lag_s", a.silhouette_lag_s);
  EmitInt(out, "silhouette_min_rows", a.silhouette_min_rows);
  EmitNumber(out, "silhouette_growth_px", a.silhouette_growth_px);
  EmitNumber(out, "silhouette_behind_m", a.silhouette_behind_m);
  out << YAML::EndMap;
  out << YAML::EndMap;

  const LegOdometrySettings& lo = s.lo;
  out << YAML::Key << "lo" << YAML::Value << YAML::BeginMap;
  EmitWord(out, "contact", lo.contact);
  EmitWord(out, "imu_sampling", lo.imu_sampling);
  EmitWord(out, "slip_reference", lo.slip_reference);
  EmitNumber(out, "attitude_gain", lo.attitude_gain);
  EmitNumber(out, "gyro_bias_gain", lo.gyro_bias_gain);
  EmitNumber(out, "gravity_gate_mps2", lo.gravity_gate_mps2);
  EmitNumber(out, "attitude_accel_average_s", lo.attitude_accel_average_s);
  EmitNumber(out, "accel_noise", lo.accel_noise);
  EmitNumber(out, "stance_foot_noise", lo.stance_foot_noise);
  EmitNumber(out, "swing_foot_noise", lo.swing_foot_noise);
  EmitNumber(out, "kin_position_noise_m", lo.kin_position_noise_m);
  EmitNumber(out, "kin_velocity_noise_mps", lo.kin_velocity_noise_mps);
  EmitNumber(out, "velocity_window_s", lo.velocity_window_s);
  EmitNumber(out, "touchdown_s", lo.touchdown_s);
  EmitNumber(out, "touchdown_inflation", lo.touchdown_inflation);
  EmitNumber(out, "touchdown_inflation_vertical", lo.touchdown_inflation_vertical);
  EmitNumber(out, "slip_gate_chi2", lo.slip_gate_chi2);
  EmitNumber(out, "slip_min_window_s", lo.slip_min_window_s);
  EmitNumber(out, "contact_height_m", lo.contact_height_m);
  EmitInt(out, "fusion_min_inliers", lo.fusion_min_inliers);
  EmitNumber(out, "fusion_tilt_gate_deg", lo.fusion_tilt_gate_deg);
  EmitNumber(out, "fusion_tilt_carry_gate_deg", lo.fusion_tilt_carry_gate_deg);
  EmitNumber(out, "fusion_tilt_window_s", lo.fusion_tilt_window_s);
  EmitBool(out, "fusion_hold_gravity", lo.fusion_hold_gravity);
  EmitNumber(out, "fusion_gyro_bias_s", lo.fusion_gyro_bias_s);
  EmitNumber(out, "slip_speed_mps", lo.slip_speed_mps);
  EmitNumber(out, "slip_travel_m", lo.slip_travel_m);
  EmitNumber(out, "slip_travel_from_s", lo.slip_travel_from_s);
  EmitNumber(out, "yaw_bias_initial_std", lo.yaw_bias_initial_std);
  EmitNumber(out, "yaw_bias_walk", lo.yaw_bias_walk);
  EmitNumber(out, "yaw_pair_noise_m", lo.yaw_pair_noise_m);
  EmitNumber(out, "yaw_pair_min_s", lo.yaw_pair_min_s);
  EmitNumber(out, "yaw_pair_max_s", lo.yaw_pair_max_s);
  EmitNumber(out, "yaw_pair_max_rate_radps", lo.yaw_pair_max_rate_radps);
  EmitNumber(out, "yaw_pair_gate_chi2", lo.yaw_pair_gate_chi2);
  out << YAML::EndMap;

  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace viqu::slam

// Strict SLAM settings loading: default.yaml equals the struct defaults, round trip through
// SlamSettingsToYaml, --set overrides, and FILE:LINE:COL errors.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "slam/core/dynamic_objects.h"
#include "slam/settings/slam_settings.h"

namespace viqu::slam {
namespace {

namespace fs = std::filesystem;

class SlamSettingsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "viqu_slam_settings_XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  // The InputError message of loading `yaml` (written as slam.yaml) with `overrides`, or a
  // failure marker when no InputError is thrown.
  std::string ErrorOf(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
    const std::string path = Write("slam.yaml", yaml);
    try {
      LoadSlamSettings(path, overrides);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no InputError>";
  }

  std::string Path() const { return (dir_ / "slam.yaml").string(); }

  fs::path dir_;
};

// Every field (source_file excepted), compared exactly.
void ExpectSameSettings(const SlamSettings& a, const SlamSettings& b) {
  EXPECT_EQ(a.input, b.input);
  EXPECT_EQ(a.rgbd_max_depth_m, b.rgbd_max_depth_m);
  EXPECT_EQ(a.rgbd_virtual_baseline_m, b.rgbd_virtual_baseline_m);

  EXPECT_EQ(a.orb.num_features, b.orb.num_features);
  EXPECT_EQ(a.orb.scale_factor, b.orb.scale_factor);
  EXPECT_EQ(a.orb.num_levels, b.orb.num_levels);
  EXPECT_EQ(a.orb.fast_threshold, b.orb.fast_threshold);
  EXPECT_EQ(a.orb.fast_threshold_min, b.orb.fast_threshold_min);
  EXPECT_EQ(a.orb.cell_px, b.orb.cell_px);
  EXPECT_EQ(a.orb.level_pixel_centres, b.orb.level_pixel_centres);
  EXPECT_EQ(a.stereo.level_pixel_centres, b.stereo.level_pixel_centres);

  EXPECT_EQ(a.stereo.max_hamming, b.stereo.max_hamming);
  EXPECT_EQ(a.stereo.row_band_px, b.stereo.row_band_px);
  EXPECT_EQ(a.stereo.sad_half_window, b.stereo.sad_half_window);
  EXPECT_EQ(a.stereo.sad_search_px, b.stereo.sad_search_px);
  EXPECT_EQ(a.stereo.max_ratio, b.stereo.max_ratio);
  EXPECT_EQ(a.stereo.min_depth_m, b.stereo.min_depth_m);
  EXPECT_EQ(a.stereo.max_depth_baselines, b.stereo.max_depth_baselines);
  EXPECT_EQ(a.stereo.scale_factor, b.stereo.scale_factor);
  EXPECT_EQ(a.stereo.sad_outlier_factor, b.stereo.sad_outlier_factor);
  EXPECT_EQ(a.stereo.sad_uniqueness, b.stereo.sad_uniqueness);
  EXPECT_EQ(a.stereo.subpixel, b.stereo.subpixel);
  EXPECT_EQ(a.stereo.max_shear, b.stereo.max_shear);
  EXPECT_EQ(a.stereo.shear_step, b.stereo.shear_step);
  EXPECT_EQ(a.stereo.lr_check_px, b.stereo.lr_check_px);
  EXPECT_EQ(a.stereo.near_mono_baselines, b.stereo.near_mono_baselines);
  EXPECT_EQ(a.stereo.near_right_weight_tracking, b.stereo.near_right_weight_tracking);
  EXPECT_EQ(a.stereo.near_right_weight_ba, b.stereo.near_right_weight_ba);

  const TrackingSettings& ta = a.tracking;
  const TrackingSettings& tb = b.tracking;
  EXPECT_EQ(ta.motion_search_px, tb.motion_search_px);
  EXPECT_EQ(ta.local_map_search_px, tb.local_map_search_px);
  EXPECT_EQ(ta.max_hamming, tb.max_hamming);
  EXPECT_EQ(ta.match_ratio, tb.match_ratio);
  EXPECT_EQ(ta.min_inliers, tb.min_inliers);
  EXPECT_EQ(ta.min_inliers_motion, tb.min_inliers_motion);
  EXPECT_EQ(ta.local_keyframes, tb.local_keyframes);
  EXPECT_EQ(ta.spatial_keyframes, tb.spatial_keyframes);
  EXPECT_EQ(ta.spatial_radius_m, tb.spatial_radius_m);
  EXPECT_EQ(ta.spatial_max_angle_deg, tb.spatial_max_angle_deg);
  EXPECT_EQ(ta.huber_px, tb.huber_px);
  EXPECT_EQ(ta.pose_iterations, tb.pose_iterations);
  EXPECT_EQ(ta.keyframe_max_frames, tb.keyframe_max_frames);
  EXPECT_EQ(ta.keyframe_min_frames, tb.keyframe_min_frames);
  EXPECT_EQ(ta.keyframe_ratio, tb.keyframe_ratio);
  EXPECT_EQ(ta.close_points_min, tb.close_points_min);
  EXPECT_EQ(ta.relocalise_min_inliers, tb.relocalise_min_inliers);
  EXPECT_EQ(ta.close_tracked_max, tb.close_tracked_max);
  EXPECT_EQ(ta.relocalise_ransac_min_inliers, tb.relocalise_ransac_min_inliers);
  EXPECT_EQ(ta.init_min_points, tb.init_min_points);
  EXPECT_EQ(ta.keyframe_new_points, tb.keyframe_new_points);
  EXPECT_EQ(ta.keyframe_min_inliers, tb.keyframe_min_inliers);
  EXPECT_EQ(ta.reinitialise_after_lost, tb.reinitialise_after_lost);
  EXPECT_EQ(ta.lost_carry_min_inliers, tb.lost_carry_min_inliers);
  EXPECT_EQ(ta.weak_inliers_factor, tb.weak_inliers_factor);
  EXPECT_EQ(ta.relocalised_frames, tb.relocalised_frames);
  EXPECT_EQ(ta.relocalised_min_inliers, tb.relocalised_min_inliers);
  EXPECT_EQ(ta.prior_window_factor, tb.prior_window_factor);
  EXPECT_EQ(ta.prior_window_frames, tb.prior_window_frames);
  EXPECT_EQ(ta.prior_window_min_px, tb.prior_window_min_px);

  const MappingSettings& ma = a.mapping;
  const MappingSettings& mb = b.mapping;
  EXPECT_EQ(ma.mode, mb.mode);
  EXPECT_EQ(ma.ba_window, mb.ba_window);
  EXPECT_EQ(ma.ba_iterations, mb.ba_iterations);
  EXPECT_EQ(ma.ba_huber_px, mb.ba_huber_px);
  EXPECT_EQ(ma.covisibility_min, mb.covisibility_min);
  EXPECT_EQ(ma.triangulation_neighbours, mb.triangulation_neighbours);
  EXPECT_EQ(ma.min_parallax_deg, mb.min_parallax_deg);
  EXPECT_EQ(ma.culling_found_ratio, mb.culling_found_ratio);
  EXPECT_EQ(ma.redundant_keyframe_ratio, mb.redundant_keyframe_ratio);
  EXPECT_EQ(a.mode, b.mode);
  const DynamicSettings &da = a.dynamic, &db = b.dynamic;
  EXPECT_EQ(da.method, db.method);
  EXPECT_EQ(da.alpha, db.alpha);
  EXPECT_EQ(da.beta, db.beta);
  EXPECT_EQ(da.gamma, db.gamma);
  EXPECT_EQ(da.th_d, db.th_d);
  EXPECT_EQ(da.window_s, db.window_s);
  EXPECT_EQ(da.window_n, db.window_n);
  EXPECT_EQ(da.forget_s, db.forget_s);
  EXPECT_EQ(da.keep_past_observations, db.keep_past_observations);
  EXPECT_EQ(da.prior.person, db.prior.person);
  EXPECT_EQ(da.prior.box, db.prior.box);
  EXPECT_EQ(da.prior.ball, db.prior.ball);
  EXPECT_EQ(da.adaptive.lag_s, db.adaptive.lag_s);
  EXPECT_EQ(da.adaptive.threshold_m, db.adaptive.threshold_m);
  EXPECT_EQ(da.adaptive.k_sigma, db.adaptive.k_sigma);
  EXPECT_EQ(da.adaptive.disparity_sigma_px, db.adaptive.disparity_sigma_px);
  EXPECT_EQ(da.adaptive.pixel_sigma_px, db.adaptive.pixel_sigma_px);
  EXPECT_EQ(da.adaptive.hold_s, db.adaptive.hold_s);
  EXPECT_EQ(da.adaptive.max_speed_mps, db.adaptive.max_speed_mps);
  EXPECT_EQ(da.adaptive.still_max_m, db.adaptive.still_max_m);
  EXPECT_EQ(da.adaptive.confirm_frames, db.adaptive.confirm_frames);
  EXPECT_EQ(da.adaptive.drop_frames, db.adaptive.drop_frames);
  EXPECT_EQ(da.adaptive.static_pose_outliers, db.adaptive.static_pose_outliers);
  EXPECT_EQ(da.adaptive.min_matches, db.adaptive.min_matches);
  EXPECT_EQ(da.adaptive.foreground_band_m, db.adaptive.foreground_band_m);
  EXPECT_EQ(da.adaptive.interior_px, db.adaptive.interior_px);
  EXPECT_EQ(da.adaptive.max_hamming, db.adaptive.max_hamming);
  EXPECT_EQ(da.adaptive.static_pose_min_share, db.adaptive.static_pose_min_share);
  EXPECT_EQ(da.adaptive.stop_max_m, db.adaptive.stop_max_m);
  EXPECT_EQ(da.adaptive.changed_look_frames, db.adaptive.changed_look_frames);
  EXPECT_EQ(da.adaptive.silhouette_threshold_m, db.adaptive.silhouette_threshold_m);
  EXPECT_EQ(da.adaptive.silhouette_lag_s, db.adaptive.silhouette_lag_s);
  EXPECT_EQ(da.adaptive.silhouette_min_rows, db.adaptive.silhouette_min_rows);
  EXPECT_EQ(da.adaptive.silhouette_growth_px, db.adaptive.silhouette_growth_px);
  EXPECT_EQ(da.adaptive.silhouette_behind_m, db.adaptive.silhouette_behind_m);
}

// Number of "key: value" lines (not counting section headers) in YAML text.
int CountLeafKeys(const std::string& yaml) {
  int n = 0;
  size_t start = 0;
  while (start < yaml.size()) {
    size_t end = yaml.find('\n', start);
    if (end == std::string::npos) end = yaml.size();
    std::string line = yaml.substr(start, end - start);
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line = line.substr(0, hash);
    const size_t colon = line.find(':');
    if (colon != std::string::npos && line.find_first_not_of(" \t", colon + 1) != std::string::npos) ++n;
    start = end + 1;
  }
  return n;
}

// The number of fields of SlamSettings that are keys (all but source_file); dynamic: 9 + 3 priors + 23 adaptive;
// lo: 35.
constexpr int kLeafKeys = 4 + 7 + 17 + 30 + 9 + 9 + 3 + 23 + 35;

TEST_F(SlamSettingsTest, DefaultFileEqualsStructDefaults) {
  const std::string path = DefaultSlamSettingsPath();
  ASSERT_TRUE(fs::is_regular_file(path)) << path;
  const SlamSettings s = LoadSlamSettings(path);
  ExpectSameSettings(s, SlamSettings());
  EXPECT_EQ(s.source_file, fs::path(path).lexically_normal().string());
  // Every key is written out in the default file.
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(CountLeafKeys(text), kLeafKeys);
}

// The shipped opt-in file for the stereo matcher's accuracy options (docs/MEASURED.md "Stereo defaults,
// session 32") loads and changes exactly those keys.
TEST_F(SlamSettingsTest, StereoGroundFileChangesOnlyTheStereoAccuracyKeys) {
  const fs::path path = fs::path(DefaultSlamSettingsPath()).parent_path() / "stereo_ground.yaml";
  ASSERT_TRUE(fs::is_regular_file(path)) << path;
  const SlamSettings s = LoadSlamSettings(path.string());
  SlamSettings expected;
  expected.orb.level_pixel_centres = true;
  expected.stereo.level_pixel_centres = true;  // follows orb.level_pixel_centres
  expected.stereo.subpixel = "equiangular";
  expected.stereo.max_shear = 0.6;
  ExpectSameSettings(s, expected);
  EXPECT_NE(s.stereo.subpixel, SlamSettings().stereo.subpixel);  // not already the defaults
  EXPECT_NE(s.stereo.max_shear, SlamSettings().stereo.max_shear);
}

TEST_F(SlamSettingsTest, EmptyFileGivesDefaults) {
  const SlamSettings s = LoadSlamSettings(Write("slam.yaml", ""));
  ExpectSameSettings(s, SlamSettings());
  EXPECT_EQ(s.source_file, Path());
  ExpectSameSettings(LoadSlamSettings(Write("slam.yaml", "tracking: {}\nmapping:\n")), SlamSettings());
}

TEST_F(SlamSettingsTest, DefaultsRoundTrip) {
  const std::string yaml = SlamSettingsToYaml(SlamSettings());
  EXPECT_EQ(CountLeafKeys(yaml), kLeafKeys) << yaml;
  ExpectSameSettings(LoadSlamSettings(Write("saved.yaml", yaml)), SlamSettings());
}

TEST_F(SlamSettingsTest, NonDefaultValuesRoundTrip) {
  SlamSettings s;
  s.input = "rgbd";
  s.rgbd_max_depth_m = 4.123456789012345;
  s.rgbd_virtual_baseline_m = 0.1 + 0.2;  // not the shortest decimal of its neighbours
  s.orb = {2000, 1.3, 6, 25, 5, 40, true};
  s.stereo.level_pixel_centres = true;  // read from orb.level_pixel_centres
  s.stereo.max_hamming = 60;
  s.stereo.row_band_px = 0;
  s.stereo.sad_half_window = 3;
  s.stereo.sad_search_px = 7;
  s.stereo.max_ratio = 1;
  s.stereo.min_depth_m = 0.05;
  s.stereo.max_depth_baselines = 55.5;
  s.stereo.scale_factor = 1.3;
  s.stereo.sad_outlier_factor = 3;
  s.stereo.sad_uniqueness = 0.5;
  s.stereo.subpixel = "parabola";
  s.stereo.max_shear = 0.35;
  s.stereo.shear_step = 0.05;
  s.stereo.lr_check_px = 0.75;
  s.stereo.near_mono_baselines = 12.5;
  s.stereo.near_right_weight_tracking = 0.125;
  s.stereo.near_right_weight_ba = 0.375;
  s.tracking = {12.5, 3.25, 90, 0.8, 25, 15, 8, 1.5, 3, 30, 2, 0.6, 50, 35};
  s.mapping.mode = "realtime";
  s.mapping.ba_window = 7;
  s.mapping.ba_iterations = 20;
  s.mapping.ba_huber_px = 3;
  s.mapping.covisibility_min = 10;
  s.mapping.triangulation_neighbours = 12;
  s.mapping.min_parallax_deg = 0.5;
  s.mapping.culling_found_ratio = 0;
  s.mapping.redundant_keyframe_ratio = 0.95;
  s.mode = "visual_dynamic";
  s.dynamic.method = "paper";
  s.dynamic.alpha = 0.7;
  s.dynamic.beta = 1.3;
  s.dynamic.gamma = 0.25;
  s.dynamic.th_d = 0.05;
  s.dynamic.window_s = 1.5;
  s.dynamic.window_n = 12;
  s.dynamic.forget_s = 3;
  s.dynamic.keep_past_observations = false;
  s.dynamic.prior = {0.9, 0.1, 0.4};
  s.dynamic.adaptive = {0.8, 0.03, 2.5, 0.7, 0.4, 2.5, 0.15, 0.7, 3, 2, 8, 4, 0.25, 40, 0.3, 0, 0.02, 3, 0.01, 0.2, 12, 1.5, 0.4};
  s.source_file = "/some/where.yaml";

  const std::string yaml = SlamSettingsToYaml(s);
  const SlamSettings back = LoadSlamSettings(Write("saved.yaml", yaml));
  ExpectSameSettings(back, s);
  EXPECT_EQ(back.source_file, (dir_ / "saved.yaml").string());
  // Saving again gives the same text, apart from the header comment naming the source.
  SlamSettings again = back;
  again.source_file = s.source_file;
  EXPECT_EQ(SlamSettingsToYaml(again), yaml);
}

TEST_F(SlamSettingsTest, OverrideSetsOneKeyAndKeepsTheRest) {
  const SlamSettings s = LoadSlamSettings(DefaultSlamSettingsPath(), {"tracking.min_inliers=50"});
  EXPECT_EQ(s.tracking.min_inliers, 50);
  SlamSettings expected;
  expected.tracking.min_inliers = 50;
  ExpectSameSettings(s, expected);
}

TEST_F(SlamSettingsTest, OverridesCreateSectionsAndPartialFilesKeepDefaults) {
  const std::string path = Write("slam.yaml", "orb:\n  num_features: 800\n");
  const SlamSettings s = LoadSlamSettings(path, {"mapping.mode=realtime", "input=rgbd", "stereo.max_ratio=0.8"});
  SlamSettings expected;
  expected.orb.num_features = 800;
  expected.mapping.mode = "realtime";
  expected.input = "rgbd";
  expected.stereo.max_ratio = 0.8;
  ExpectSameSettings(s, expected);
}

TEST_F(SlamSettingsTest, UnknownKeyNamesFileLineAndColumn) {
  const std::string msg = ErrorOf(
      "input: stereo\n"
      "tracking:\n"
      "  min_inliers: 30\n"
      "  min_inlier: 5\n");
  EXPECT_EQ(msg.rfind(Path() + ":4:3: unknown key 'tracking.min_inlier' (expected one of: motion_search_px, ", 0),
            0u)
      << msg;
  EXPECT_NE(msg.find("prior_window_min_px)"), std::string::npos) << msg;  // the list ends with the last key
}

TEST_F(SlamSettingsTest, UnknownKeysAtTopLevelAndInEverySection) {
  EXPECT_EQ(ErrorOf("input: stereo\nloop_closing: true\n").rfind(Path() + ":2:1: unknown key 'loop_closing'", 0), 0u);
  EXPECT_EQ(ErrorOf("orb: {nfeatures: 10}\n").rfind(Path() + ":1:7: unknown key 'orb.nfeatures'", 0), 0u);
  EXPECT_EQ(ErrorOf("stereo:\n    sad_window: 3\n").rfind(Path() + ":2:5: unknown key 'stereo.sad_window'", 0), 0u);
  EXPECT_EQ(ErrorOf("stereo:\n  subpixel: cubic\n"),
            Path() + ":2:13: key 'stereo.subpixel' expected one of parabola, equiangular, got 'cubic'");
  EXPECT_EQ(ErrorOf("stereo: {max_shear: -0.1}\n").rfind(Path() + ":1:21: key 'stereo.max_shear' expected a number in [0, 2], got '-0.1'", 0), 0u);
  EXPECT_EQ(ErrorOf("mapping:\n  ba_windows: 3\n").rfind(Path() + ":2:3: unknown key 'mapping.ba_windows'", 0), 0u);
  const std::string set = ErrorOf("", {"tracking.min_inlier=5"});
  EXPECT_EQ(set.rfind("--set tracking.min_inlier=5: unknown key 'tracking.min_inlier'", 0), 0u) << set;
}

TEST_F(SlamSettingsTest, DynamicKeysAreCheckedLikeTheRest) {
  EXPECT_EQ(ErrorOf("dynamic:\n  method: magic\n"),
            Path() + ":2:11: key 'dynamic.method' expected one of none, semantic, paper, adaptive, got 'magic'");
  EXPECT_EQ(ErrorOf("dynamic:\n  adaptive: {lag: 1}\n").rfind(Path() + ":2:14: unknown key 'dynamic.adaptive.lag'", 0), 0u);
  EXPECT_EQ(ErrorOf("mode: dynamic\n"),
            Path() + ":1:7: key 'mode' expected one of visual, visual_dynamic, full, got 'dynamic'");
  EXPECT_EQ(ErrorOf("dynamic: {prior: {person: 1.5}}\n"),
            Path() + ":1:27: key 'dynamic.prior.person' expected a number in [0, 1], got '1.5'");
  const SlamSettings s = LoadSlamSettings(DefaultSlamSettingsPath(), {"dynamic.method=none", "mode=visual_dynamic"});
  EXPECT_EQ(s.dynamic.method, "none");
  EXPECT_EQ(DynamicMethodOf(s), DynamicMethod::kNone);
  EXPECT_EQ(DynamicMethodOf(SlamSettings()), DynamicMethod::kAdaptive);
}

TEST_F(SlamSettingsTest, WrongType) {
  EXPECT_EQ(ErrorOf("tracking:\n  min_inliers: many\n"),
            Path() + ":2:16: key 'tracking.min_inliers' expected an integer in [3, 100000], got 'many'");
  EXPECT_EQ(ErrorOf("orb: {num_levels: 7.5}\n"),
            Path() + ":1:19: key 'orb.num_levels' expected an integer in [1, 32], got '7.5'");
  EXPECT_EQ(ErrorOf("stereo: {min_depth_m: \"0.1\"}\n"),
            Path() + ":1:23: key 'stereo.min_depth_m' expected a number > 0, got '\"0.1\"' (a quoted string)");
  EXPECT_EQ(ErrorOf("mapping: [1, 2]\n"), Path() + ":1:10: key 'mapping' expected a map, got a list");
  EXPECT_EQ(ErrorOf("mapping: {mode: async}\n"),
            Path() + ":1:17: key 'mapping.mode' expected one of sync, realtime, got 'async'");
  EXPECT_EQ(ErrorOf("input: mono\n"), Path() + ":1:8: key 'input' expected one of stereo, rgbd, got 'mono'");
  EXPECT_EQ(ErrorOf("", {"tracking.huber_px=wide"}),
            "--set tracking.huber_px=wide: key 'tracking.huber_px' expected a number > 0, got 'wide'");
}

TEST_F(SlamSettingsTest, OutOfRange) {
  EXPECT_EQ(ErrorOf("tracking:\n  match_ratio: 1.5\n"),
            Path() + ":2:16: key 'tracking.match_ratio' expected a number in (0, 1], got '1.5'");
  EXPECT_EQ(ErrorOf("orb:\n  num_features: 0\n"),
            Path() + ":2:17: key 'orb.num_features' expected an integer in [1, 100000], got '0'");
  EXPECT_EQ(ErrorOf("orb: {scale_factor: 1, num_levels: 1}\nstereo: {scale_factor: 1}\n"),
            Path() + ":1:21: key 'orb.scale_factor' expected a number in (1, 4], got '1'");
  EXPECT_EQ(ErrorOf("rgbd_max_depth_m: -2\n"),
            Path() + ":1:19: key 'rgbd_max_depth_m' expected a number > 0, got '-2'");
  EXPECT_EQ(ErrorOf("stereo:\n  max_hamming: 300\n"),
            Path() + ":2:16: key 'stereo.max_hamming' expected an integer in [1, 256], got '300'");
  EXPECT_EQ(ErrorOf("mapping:\n  culling_found_ratio: -0.1\n"),
            Path() + ":2:24: key 'mapping.culling_found_ratio' expected a number in [0, 1], got '-0.1'");
}

TEST_F(SlamSettingsTest, CrossFieldChecks) {
  const std::string fast = ErrorOf("orb:\n  fast_threshold: 10\n  fast_threshold_min: 12\n");
  EXPECT_EQ(fast.rfind(Path() + ":3:23: key 'orb.fast_threshold_min' (12) must not exceed 'orb.fast_threshold' (10)",
                       0),
            0u)
      << fast;
  // Only the threshold is in the file: the message points at it.
  const std::string fast2 = ErrorOf("orb:\n  fast_threshold: 5\n");
  EXPECT_EQ(fast2.rfind(Path() + ":2:19: key 'orb.fast_threshold_min' (7) must not exceed", 0), 0u) << fast2;

  const std::string kf = ErrorOf("tracking: {keyframe_min_frames: 30}\n");
  EXPECT_EQ(kf.rfind(Path() + ":1:33: key 'tracking.keyframe_min_frames' (30) must not exceed", 0), 0u) << kf;

  // The stereo matcher must work on the extractor's pyramid.
  const std::string scale = ErrorOf("orb:\n  scale_factor: 1.3\n");
  EXPECT_EQ(scale.rfind(Path() + ":2:17: key 'stereo.scale_factor' (1.2) must equal 'orb.scale_factor' (1.3)", 0), 0u)
      << scale;
  const std::string scale2 = ErrorOf("orb: {scale_factor: 1.3}\nstereo: {scale_factor: 1.25}\n");
  EXPECT_EQ(scale2.rfind(Path() + ":2:24: key 'stereo.scale_factor' (1.25) must equal 'orb.scale_factor' (1.3)", 0),
            0u)
      << scale2;
  const std::string scale3 = ErrorOf("", {"orb.scale_factor=1.5"});
  EXPECT_EQ(scale3.rfind("--set orb.scale_factor=1.5: key 'stereo.scale_factor' (1.2) must equal", 0), 0u) << scale3;
  // Both set alike: fine.
  const SlamSettings s =
      LoadSlamSettings(Write("slam.yaml", "orb: {scale_factor: 1.5}\n"), {"stereo.scale_factor=1.5"});
  EXPECT_EQ(s.orb.scale_factor, 1.5);
  EXPECT_EQ(s.stereo.scale_factor, 1.5);
}

TEST_F(SlamSettingsTest, DuplicateKey) {
  EXPECT_EQ(ErrorOf("tracking:\n  min_inliers: 30\n  min_inliers: 40\n"),
            Path() + ":3:3: duplicate key 'tracking.min_inliers'");
}

TEST_F(SlamSettingsTest, MissingFile) {
  const std::string path = (dir_ / "nope.yaml").string();
  try {
    LoadSlamSettings(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": file not found");
  }
}

TEST_F(SlamSettingsTest, MalformedYamlNamesLineAndColumn) {
  const std::string msg = ErrorOf("input: stereo\n  bad: 2\n");
  EXPECT_EQ(msg.rfind(Path() + ":2:6: YAML syntax error: ", 0), 0u) << msg;
  const std::string msg2 = ErrorOf("orb: {num_features: 10\ntracking: {}\n");
  EXPECT_EQ(msg2.rfind(Path() + ":", 0), 0u) << msg2;
  EXPECT_NE(msg2.find("YAML syntax error"), std::string::npos) << msg2;
  EXPECT_EQ(ErrorOf("[1, 2]\n"), Path() + ":1:1: the document expected a map, got a list");
}

}  // namespace
}  // namespace viqu::slam

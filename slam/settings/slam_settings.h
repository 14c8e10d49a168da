#pragma once
// Settings of the SLAM system, as read from a YAML file (slam/config/default.yaml holds every
// key with its default). Loading is strict: an unknown key, a wrong type or an out-of-range value
// is an InputError naming the file, line and column.
#include <string>
#include <vector>

#include "slam/features/orb_extractor.h"
#include "slam/features/stereo_matcher.h"

namespace viqu::slam {

struct TrackingSettings {
  double motion_search_px = 15;      // window radius for matching with the motion model (px, level 0)
  double local_map_search_px = 4;    // window radius for local-map projection (px, times scale)
  int max_hamming = 100;             // descriptor distance accepted in projection search (bits)
  double match_ratio = 0.9;          // best / second-best distance for window searches
  int min_inliers = 30;              // pose-only inliers below this: the frame is lost
  int min_inliers_motion = 20;       // motion-model matches below this: fall back to the keyframe
  int local_keyframes = 20;          // covisible keyframes whose points form the local map
  double huber_px = 2.447;           // robust kernel width, sqrt(chi2 2 dof 95%) (px)
  int pose_iterations = 4;           // rounds of optimise / reclassify outliers
  // Keyframe decision (ORB-SLAM's criteria, in frames at camera rate)
  int keyframe_max_frames = 20;      // a keyframe at least this often
  int keyframe_min_frames = 0;       // never more often than this
  double keyframe_ratio = 0.75;      // tracked points of the reference keyframe below this share
  int close_points_min = 70;         // near stereo points not tracked above this (with few tracked): keyframe
  int relocalise_min_inliers = 40;   // pose inliers after a relocalisation's local search to accept it
  int close_tracked_max = 100;       // near stereo points tracked below this, with close_points_min new ones: keyframe (count)
  int relocalise_ransac_min_inliers = 12;// PnP RANSAC inliers for a relocalisation candidate to be refined (count)
  int init_min_points = 100;         // stereo points needed to start a map or a new segment (count)
  int keyframe_new_points = 100;     // a new keyframe makes map points of at least its this many nearest stereo features (count)
  int keyframe_min_inliers = 50;     // a frame tracked with fewer inliers never becomes a keyframe (count)
  int reinitialise_after_lost = 20;  // lost frames in a row after which a frame that does not relocalise starts a new segment (frames)
  int lost_carry_min_inliers = 15;   // a lost frame (no external prior) takes its pose from the last frame's stereo points when
                                     // this many are inliers, not from the constant velocity (count; 0: off)
  double weak_inliers_factor = 3;    // fewer inliers than this times min_inliers: search again with windows 3x as wide (ratio)
  int relocalised_frames = 20;       // frames after a relocalisation that need relocalised_min_inliers and make no keyframe (frames)
  int relocalised_min_inliers = 50;  // inliers a frame needs within relocalised_frames after a relocalisation (count)
  // With an external motion prior (mode full: leg odometry + IMU, or the gyro) the first window is
  // sized from the prior's error instead of motion_search_px: prior_window_factor times the larger
  // of (the largest 90th-percentile miss of the prior, in pixels, over the last prior_window_frames
  // frames) and (the filter's velocity uncertainty over the frame interval, projected at the
  // scene's median depth), within [prior_window_min_px, 3 * motion_search_px]. The default
  // minimum is motion_search_px: the window only widens (narrower windows, 4-6 px, tracked
  // faster but measured worse: static_room 30 s over 4 seeds 2.57 against 2.10 mm mean).
  double prior_window_factor = 2;    // (ratio)
  int prior_window_frames = 20;      // (frames)
  double prior_window_min_px = 15;   // (px, level 0)
  // Keyframes near the camera that covisibility does not reach (a place seen again after a loop)
  // join the local map, nearest first, so that the old map is matched instead of mapped again.
  int spatial_keyframes = 5;         // at most this many (count; 0: off)
  double spatial_radius_m = 0.5;     // camera centres at most this far apart (m)
  double spatial_max_angle_deg = 30; // optical axes at most this far apart (deg)
};

struct MappingSettings {
  std::string mode = "sync";         // sync (inline, deterministic) | realtime (second thread)
  int ba_window = 10;                // keyframes optimised by local BA (covisibility order)
  int ba_iterations = 10;            // Levenberg-Marquardt iterations per local BA
  double ba_huber_px = 2.447;        // robust kernel (px)
  int covisibility_min = 15;         // shared points for a covisibility edge
  int triangulation_neighbours = 10; // keyframes searched for new points
  double min_parallax_deg = 1.0;     // triangulation needs at least this ray angle (deg)
  double culling_found_ratio = 0.25; // a point found in fewer than this share of frames it was visible in is culled
  double redundant_keyframe_ratio = 0.9;  // a keyframe whose points are seen by 3 others in this share is culled
};

// Per-category prior Pr_k of eq. 3 (how likely an object of the category moves, 0-1).
struct CategoryPriors {
  double person = 1.0;
  double box = 0.3;
  double ball = 0.6;
};

// The `adaptive` method: an object is dynamic when the median world displacement of its matched
// features over `lag_s` exceeds a threshold that grows with stereo depth uncertainty.
struct AdaptiveDynamicSettings {
  double lag_s = 1.0;                // features are compared with the object's features this long ago (s)
  double threshold_m = 0.02;         // displacement beyond noise that makes an object dynamic (m)
  double k_sigma = 3.0;              // plus this many standard errors of the displacement (count)
  double disparity_sigma_px = 0.5;   // stereo disparity noise behind the standard error along the ray (px)
  double pixel_sigma_px = 0.5;       // keypoint position noise behind the standard error across the ray
                                     // (px at pyramid level 0, times the level's scale)
  double max_speed_mps = 3;          // a median displacement faster than this is a mismatch, no motion (m/s)
  double still_max_m = 0.2;          // judged still only when displacement + k_sigma std errors is below this (m)
  double hold_s = 1.0;               // a dynamic object stays dynamic this long after its last motion (s)
  int confirm_frames = 2;            // consecutive judgements of motion before an object turns dynamic (frames)
  int drop_frames = 1;               // consecutive judgements of motion after which its features are dropped
                                     // (frames): below confirm_frames the object is tentatively dynamic, dropped
                                     // but not held and its map points kept, until confirmed
  int min_matches = 6;               // matched features needed to judge an object (count)
  int interior_px = 6;               // features nearer than this to the mask's edge are not judged: corners on
                                     // the silhouette mix the object with the background behind it (px)
  double foreground_band_m = 0.3;    // features deeper than the object's first depth quartile plus this are
                                     // background seen through the loose mask, not the object; those nearer
                                     // than its densest band of this width by more than this are stereo
                                     // mismatches (m)
  int max_hamming = 50;              // descriptor distance for matching an object's features over time (bits)
  double static_pose_min_share = 0.2;  // movable objects carry this share of inliers: judge with a pose from the rest (ratio)
  int static_pose_outliers = 1;      // 1: that pose takes back the static matches the tracked pose rejected (a large
                                     // moving object drags the tracked pose along); 0: the tracked inliers only
  double stop_max_m = 0.01;          // a still look whose median displacement is below this dates the object's
                                     // last motion no later than the look's start: the hold runs from there (m)
  int changed_look_frames = 2;       // within hold_s of a release, this many looks in a row that cannot be judged
                                     // (with at least min_matches features with depth) make it dynamic again
                                     // (frames; 0 = never)
  double silhouette_threshold_m = 0.015;  // before an object is dynamic, a motion of its mask's free edges across the
                                          // view beyond k_sigma standard errors and this, against the mask of
                                          // silhouette_lag_s earlier, is also a look of motion (m; 0 = off)
  double silhouette_lag_s = 0.1;     // how far back that mask is (s)
  int silhouette_min_rows = 10;      // mask edges (row ends bordering the background) needed on a side (count)
  double silhouette_growth_px = 2;   // a detector's mask grows or shrinks by up to this from frame to frame: the
                                     // shift of one side alone must exceed it (both sides cancel it) (px)
  double silhouette_behind_m = 0.3;  // a mask's end that meets another instance is the object's own edge when that
                                     // instance's median depth lies this much farther (m)
};

// Dynamic objects (paper eqs. 1-4): how objects in the segmentation masks are judged.
struct DynamicSettings {
  std::string method = "adaptive";   // none | semantic | paper | adaptive
  // The paper's eqs. 2-4 (method: paper).
  double alpha = 1.0;                // weight of the change of the labelled map points' mean norm (1)
  double beta = 1.0;                 // weight of the change of the mean mask depth (1)
  double gamma = 0.5;                // weight of the category prior (m per unit prior)
  double th_d = 0.1;                 // threshold on the change of A (m)
  double window_s = 6;               // eq. 2 window S, in seconds of frames (s)
  int window_n = 10;                 // eq. 4 window N (frames)
  CategoryPriors prior;
  AdaptiveDynamicSettings adaptive;
  double forget_s = 2.0;             // an object unseen this long starts a new history (s)
  // When an object is confirmed dynamic, its map points keep the observations of keyframes taken
  // before its motion can have begun (it stood there then, so they still tie those keyframes
  // together in BA) and are never matched again; false: they are erased with all observations.
  bool keep_past_observations = true;
};

// Leg odometry + IMU Kalman filter (paper eqs. 5-7), run in mode full. slam/lo/leg_odometry.h
// says how each value enters the filter.
struct LegOdometrySettings {
  std::string contact = "touch";     // schedule (gait's planned stance) | touch (foot sensors) | estimated
  // What one IMU reading holds: instant (the value at its time: the interval between two readings
  // takes their average rate and the earlier acceleration) | mean (the mean over the interval
  // since the previous reading, as a MEMS IMU's decimation filter gives: it is integrated over
  // that interval). A live run sets it from its scenario's sensors.imu.sampling.
  std::string imu_sampling = "instant";
  // Attitude: complementary filter on SO(3), gyro integration with a gravity correction from the
  // accelerometer (Mahony's form) and an integral term that estimates the gyro bias.
  double attitude_gain = 0.5;        // gravity correction of roll and pitch (1/s)
  double gyro_bias_gain = 0.005;     // integral gain estimating the gyro bias (1/s^2)
  double gravity_gate_mps2 = 1.5;    // no correction when |accel| differs from g by more (m/s^2)
  double attitude_accel_average_s = 0.0;  // "up" from the specific force averaged in the world over this (s; 0 = each sample)
  // Kalman filter of eq. 5 (state: body position, velocity, four feet in the world).
  double accel_noise = 0.3;          // acceleration input noise, white (m/s^2/sqrt(Hz))
  double stance_foot_noise = 0.002;  // random walk of a stance foot (m/sqrt(s))
  double swing_foot_noise = 1.0;     // random walk of a swing or slipping foot (m/sqrt(s))
  double kin_position_noise_m = 0.003;    // foot-minus-body position from kinematics (m)
  double kin_velocity_noise_mps = 0.02;   // body velocity through a stance foot, over the window (m/s)
  double velocity_window_s = 0.02;   // that velocity is the encoder positions' change over this (s)
  double touchdown_s = 0.03;         // after touch-down a foot's measurements are inflated this long (s)
  double touchdown_inflation = 10;   // by this factor on their standard deviation (ratio), horizontally
  double touchdown_inflation_vertical = 1;  // and vertically (ratio)
  // Slip: a stance foot whose velocity innovation fails this gate is slipping for that sample.
  double slip_gate_chi2 = 16.27;     // Mahalanobis gate, chi-square 3 dof at 99.9% (1)
  double slip_min_window_s = 0.01;   // a foot is judged once it has stood this long (s)
  double contact_height_m = 0.006;   // estimated: feet within this of the lowest foot are in contact (m)
  int fusion_min_inliers = 50;       // full: a frame tracked with this many inliers corrects the filter (count)
  // full: an orientation (vision's, or the filter's own while it carries the pose) whose "up" is
  // further than this from the IMU's mean specific force over fusion_tilt_window_s is levelled
  // to it (deg; 0 = off).
  double fusion_tilt_gate_deg = 2.5;
  double fusion_tilt_carry_gate_deg = 1.0;  // the same for the filter's own orientation while it carries the pose (deg; 0 = off)
  double fusion_tilt_window_s = 2.0;  // that mean's window (s)
  // full: while vision corrects the filter every frame, its attitude integrates the gyro only
  // (no gravity correction, no gyro-bias update); they resume while it carries the pose.
  bool fusion_hold_gravity = true;
  // full: the gyro bias from vision's orientation corrections: the rotation between the
  // attitude's gyro-integrated orientation and vision's, at consecutive corrections, is the
  // uncorrected bias times the interval; the estimate moves by that rotation over this time
  // constant (s; 0 = off).
  double fusion_gyro_bias_s = 5.0;
  // Slip, by speed: a stance foot whose body velocity differs from the filter's by more than this
  // over a whole velocity window is slipping, whatever the filter's own uncertainty, while another
  // stance foot agrees with the filter (m/s).
  double slip_speed_mps = 0.05;
  // Slip, by travel (the reported slip decision; the filter's gates above are unchanged by it): a
  // settled stance foot whose contact point has moved more than this horizontally since it
  // settled, against the body's travel by the filter's predictions, slipped in this stance (m).
  double slip_travel_m = 0.003;
  // The travel is counted from this long after the foot's touch-down (s).
  double slip_travel_from_s = 0.0;
  // The filter's velocity the slip gates compare a foot with, over the foot's window: position
  // (the change of the filter's position) | prediction (the body's travel by the filter's
  // predictions alone, without the jumps its measurement updates make in the position).
  std::string slip_reference = "position";
  // Gyro bias about the vertical, from pairs of stance feet: two feet that hold keep the
  // horizontal direction between them fixed in the world, so its turn in the filter's world
  // frame over a stance is the yaw the gyro bias added (slam/lo/yaw_bias_from_feet.h).
  double yaw_bias_initial_std = 0.002;  // prior std of that bias at the start (rad/s); 0 = off
  double yaw_bias_walk = 0.0001;        // its random walk (rad/s/sqrt(s))
  double yaw_pair_noise_m = 0.0003;     // noise of the horizontal vector between two feet per reading (m)
  double yaw_pair_min_s = 0.1;          // a pair's stance together must last this long to count (s)
  double yaw_pair_max_s = 1.0;          // and is cut into pieces this long while it lasts (s)
  double yaw_pair_max_rate_radps = 0.02;  // a piece turning faster than this on average is not used (rad/s)
  double yaw_pair_gate_chi2 = 9;        // a piece further from the estimate than this is dropped (chi-square, 1 dof)
};

struct SlamSettings {
  std::string source_file;           // the YAML the settings came from ("" = built-in defaults)
  std::string pyramid_where;         // where orb.num_levels / scale_factor were set (FILE:LINE:COL or
                                     // --set), for the check against the image size (PyramidProblem)
  std::string mode = "full";         // visual | visual_dynamic (plus dynamic objects) | full (plus leg odometry)
  std::string input = "stereo";      // stereo | rgbd (depth from left_depth_m)
  double rgbd_max_depth_m = 6;       // rgbd: depth beyond this is ignored (m)
  double rgbd_virtual_baseline_m = 0.08;  // rgbd: baseline of the virtual right camera (m)
  OrbExtractorOptions orb;
  StereoMatcherOptions stereo;
  TrackingSettings tracking;
  MappingSettings mapping;
  DynamicSettings dynamic;
  LegOdometrySettings lo;
};

// Reads settings from `path`. Keys not in the file keep their defaults; `overrides` are
// "key.path=value" strings applied before reading (as `--set`). Throws InputError.
// `origins[i]`, where given, is where overrides[i] came from, for messages about it (a scenario's
// key: "FILE:LINE:COL"); otherwise messages name it as "--set ...".
SlamSettings LoadSlamSettings(const std::string& path, const std::vector<std::string>& overrides = {},
                              const std::vector<std::string>& origins = {});

// Path of slam/config/default.yaml in the source tree.
std::string DefaultSlamSettingsPath();

// The settings as YAML text (every key), loadable by LoadSlamSettings.
std::string SlamSettingsToYaml(const SlamSettings& s);

}  // namespace viqu::slam

#pragma once
// One SLAM run over a stream of frames, as `viqu run` (live) and `viqu slam` (offline) both do
// it: the estimate written to trajectory_est.txt as frames come, one line per frame in
// tracking.csv (status, feature and inlier counts, keyframe, time), and
// at the end the metrics.json keys of the SLAM part (ate.*, rpe.*, tracking.*, timing.track_*),
// and dynamic.csv with the dynamic.* keys (dynamic_score.h).
#include <memory>
#include <string>
#include <vector>

#include "common/atomic_output_file.h"
#include "runner/dynamic_score.h"
#include "common/json_writer.h"
#include "sim/trajectory_writer.h"
#include "slam/core/slam_system.h"
#include "slam/fusion/gyro_motion_prior.h"
#include "slam/fusion/visual_leg_fusion.h"
#include "slam/eval/trajectory.h"

namespace viqu::runner {

struct SlamSummary {
  bool has_ate = false;
  double ate_rmse_m = 0, ate_pct_path = 0, rpe_rmse_m = 0;
  int frames = 0, lost = 0, keyframes = 0, map_points = 0;
  double track_ms_median = 0, track_ms_p95 = 0;
  std::string ate_unavailable;  // why there is ground truth but no ATE (empty otherwise)
};

class SlamRun {
 public:
  // Writes the estimate to `out_dir`/trajectory_est.txt and the per-frame log to
// `out_dir`/tracking.csv (both atomically, on Finish()).
  SlamRun(const slam::SlamSettings& settings, const std::string& out_dir,
          const Eigen::Isometry3d& world_from_first_camera = Eigen::Isometry3d::Identity());

  // Fill TrackResult::marks (the overlay video).
  void SetRecordFeatures(bool on) { system_.SetRecordFeatures(on); }

  // `truth` (live runs; null offline) scores the dynamic-object decisions in dynamic.csv.
  slam::TrackResult Track(const StereoFrame& frame, const std::vector<ObjectTruth>* truth = nullptr);

  // Waits for mapping, closes the trajectory file and adds the SLAM metrics to `json`; `gt`
  // (left camera in world) gives ATE and RPE when not empty; `path_length_m` gives
  // ate.rmse_pct_path.
  SlamSummary Finish(const eval::Trajectory& gt, double path_length_m, JsonWriter* json);

  const eval::Trajectory& estimate() const { return est_; }
  // The estimator itself (map points and keyframes for a viewer).
  const slam::SlamSystem& system() const { return system_; }

  // slam.mode full: leg odometry + IMU gives each frame's motion prior and is corrected by the
  // frames tracked well (not owned; null: vision alone).
  void SetFusion(slam::VisualLegFusion* fusion) { fusion_ = fusion; }
  // slam.mode full on a dataset with an IMU and no encoders: the gyro gives each frame's
  // rotation prior (not owned; null: none).
  void SetGyroPrior(slam::GyroMotionPrior* gyro) { gyro_ = gyro; }

 private:
  slam::SlamSystem system_;
  sim::TrajectoryWriter writer_;
  std::unique_ptr<AtomicOutputFile> log_;  // tracking.csv
  DynamicScore dynamic_;                   // dynamic.csv
  eval::Trajectory est_;
  std::vector<slam::TrackStatus> status_;
  slam::VisualLegFusion* fusion_ = nullptr;
  slam::GyroMotionPrior* gyro_ = nullptr;
  // The tracker's prediction misses (TrackResult::prior_err_*), over the frames tracked from one.
  std::vector<double> prior_err_deg_, prior_err_mm_;
  std::vector<double> search_px_;  // the first search window of each frame (px)
  int external_priors_ = 0;
  int estimated_frames_ = 0;  // frames whose pose a measurement gave (not a repeated guess)
};

// An ATE needs this many frames whose pose a measurement gave (an SE(3) alignment needs 3 poses).
constexpr int kMinEstimatedFrames = 3;

// "ATE 0.0123 m RMSE (0.41% of 3.00 m), 0 lost of 400 frames, 35 keyframes, tracking 18.2 ms median"
std::string SlamSummaryLine(const SlamSummary& s);

}  // namespace viqu::runner

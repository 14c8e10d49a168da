#include "runner/slam_run.h"

#include <cstdio>

#include "runner/run_metrics.h"
#include "common/errors.h"
#include "slam/core/dynamic_objects.h"
#include "slam/eval/trajectory_error.h"

namespace viqu::runner {

SlamRun::SlamRun(const slam::SlamSettings& settings, const std::string& out_dir,
                 const Eigen::Isometry3d& world_from_first_camera)
    : system_(settings, world_from_first_camera),
      writer_(out_dir + "/trajectory_est.txt"),
      log_(std::make_unique<AtomicOutputFile>(out_dir + "/tracking.csv")),
      dynamic_(out_dir + "/dynamic.csv") {
  log_->Write("t_s,status,features,stereo_points,inliers,keyframe,track_ms,features_dropped,dynamic_ms,"
              "motion_prior,prior_err_deg,prior_err_mm,search_px,carry_inliers,map_inliers\n");
}

slam::TrackResult SlamRun::Track(const StereoFrame& frame, const std::vector<ObjectTruth>* truth) {
  if (fusion_) fusion_->BeforeTrack(&system_);
  if (gyro_) gyro_->BeforeTrack(&system_, frame.t_ns);
  const slam::TrackResult r = system_.Track(frame);
  if (fusion_) fusion_->AfterTrack(r);
  if (gyro_) gyro_->AfterTrack(r);
  dynamic_.Add(r.t_ns, r.objects, truth);
  const StampedPose p = ToStampedPose(r.t_ns, r.T_w_c);
  writer_.Add(p);
  est_.push_back(p);
  status_.push_back(r.status);
  // The prediction's miss, blank when the frame was not tracked from a prediction.
  char miss[64] = ",";
  if (r.prior_err_deg >= 0) {
    std::snprintf(miss, sizeof miss, "%.4f,%.3f", r.prior_err_deg, r.prior_err_mm);
    prior_err_deg_.push_back(r.prior_err_deg);
    prior_err_mm_.push_back(r.prior_err_mm);
  }
  if (r.external_prior) ++external_priors_;
  // A pose measured by something: the map (tracked, relocalised, a new segment), the motion
  // prior of leg odometry + IMU or the gyro, or the last frame's own points (a carry that held).
  // A lost frame with none of these repeats a guess.
  const int carry_need = system_.settings().tracking.lost_carry_min_inliers;
  if (r.status != slam::TrackStatus::kLost || r.external_prior || (carry_need > 0 && r.carry_inliers >= carry_need)) {
    ++estimated_frames_;
  }
  char line[224];
  std::snprintf(line, sizeof line, "%s,%s,%d,%d,%d,%d,%.2f,%d,%.2f,%s,%s,%.2f,%d,%d\n", sim::FormatSeconds(r.t_ns).c_str(),
                slam::TrackStatusName(r.status), r.features, r.stereo_points, r.inliers, r.keyframe ? 1 : 0, r.track_ms,
                r.features_dropped, r.dynamic_ms, r.external_prior ? "external" : "velocity", miss, r.search_px,
                r.carry_inliers, r.map_inliers);
  search_px_.push_back(r.search_px);
  log_->Write(line);
  return r;
}

SlamSummary SlamRun::Finish(const eval::Trajectory& gt, double path_length_m, JsonWriter* json) {
  system_.Finish();
  writer_.Close();
  log_->Commit();
  dynamic_.Finish(json, slam::DynamicMethodOf(system_.settings()) != slam::DynamicMethod::kNone);
  const slam::SlamStats st = system_.Stats();
  SlamSummary s;
  s.frames = st.frames;
  s.lost = st.lost_frames;
  s.keyframes = st.keyframes;
  s.map_points = st.map_points;
  s.track_ms_median = Median(st.track_ms);
  s.track_ms_p95 = Percentile(st.track_ms, 0.95);
  json->Set("tracking.frames", st.frames);
  json->Set("tracking.lost_frames", st.lost_frames);
  json->Set("tracking.relocalisations", st.relocalisations);
  json->Set("tracking.keyframes", st.keyframes);
  json->Set("tracking.map_points", st.map_points);
  json->Set("timing.track_ms_median", s.track_ms_median);
  json->Set("timing.track_ms_p95", s.track_ms_p95);
  json->Set("timing.local_ba_ms_median", Median(st.local_ba_ms));
  json->Set("timing.local_ba_count", static_cast<int>(st.local_ba_ms.size()));
  json->Set("timing.dynamic_ms_median", Median(st.dynamic_ms));
  json->Set("timing.dynamic_ms_p95", Percentile(st.dynamic_ms, 0.95));
  json->Set("tracking.object_points_erased", st.object_points_erased);
  json->Set("tracking.object_points_retired", st.object_points_retired);
  json->Set("tracking.keyframes_freed", st.keyframes_freed);
  json->Set("tracking.map_points_freed", st.map_points_freed);
  json->Set("tracking.map_points_held", st.map_points_held);
  json->Set("tracking.map_heap_mb", static_cast<double>(st.map_heap_bytes) / (1024.0 * 1024.0));
  // How well the motion prior (leg odometry + IMU, the gyro, or the constant-velocity guess)
  // predicted each tracked frame's pose.
  json->Set("tracking.prior_frames_external", external_priors_);
  json->Set("tracking.prior_err_deg_median", Median(prior_err_deg_));
  json->Set("tracking.prior_err_deg_p95", Percentile(prior_err_deg_, 0.95));
  json->Set("tracking.prior_err_mm_median", Median(prior_err_mm_));
  json->Set("tracking.prior_err_mm_p95", Percentile(prior_err_mm_, 0.95));
  json->Set("tracking.search_px_median", Median(search_px_));
  json->Set("slam.mode", system_.settings().mode);
  json->Set("slam.dynamic_method", system_.settings().dynamic.method);
  json->Set("slam.input", system_.settings().input);
  json->Set("slam.mapping_mode", system_.settings().mapping.mode);
  json->Set("slam.settings_file", system_.settings().source_file);
  json->Set("lo.fused", fusion_ != nullptr);
  json->Set("imu.gyro_prior", gyro_ != nullptr);
  if (gyro_) json->Set("imu.gyro_priors_given", gyro_->priors_given());
  if (fusion_) {
    json->Set("lo.fusion_corrections", fusion_->corrections());
    json->Set("lo.frames_carried", fusion_->frames_carried());
    json->Set("lo.levellings", fusion_->levellings());
    json->Set("lo.fusion_bias_updates", fusion_->bias_updates());
    const Eigen::Vector3d b = fusion_->gyro_bias();
    json->SetNumbers("lo.fused_gyro_bias_radps", {b.x(), b.y(), b.z()});
  }
  if (gt.empty()) return s;
  // A trajectory that no measurement made (a camera dark throughout in `visual`: the start pose
  // repeated) has no ATE to give: its figure would describe the robot's path, not the estimator.
  if (estimated_frames_ < kMinEstimatedFrames) {
    s.ate_unavailable = std::to_string(estimated_frames_) + " of " + std::to_string(st.frames) +
                        " frames have a pose measured by the map, odometry or the last frame's points (" +
                        std::to_string(kMinEstimatedFrames) + " needed); the rest repeat a guess";
    json->Set("ate.unavailable", s.ate_unavailable);
    return s;
  }
  // The trajectory is kept whatever happens here; the metrics say why an ATE is missing.
  try {
    const eval::AteResult ate = eval::ComputeAte(est_, gt);
    const eval::ErrorStats rpe = eval::ComputeRpe(est_, gt, 1);
    json->Set("ate.rmse_m", ate.ate.rmse);
    json->Set("ate.mean_m", ate.ate.mean);
    json->Set("ate.median_m", ate.ate.median);
    json->Set("ate.std_m", ate.ate.std);
    json->Set("ate.min_m", ate.ate.min);
    json->Set("ate.max_m", ate.ate.max);
    json->Set("ate.pairs", static_cast<int64_t>(ate.pairs));
    // The same with a scale (Sim(3)): what is left once the estimate's scale error is taken
    // out, and that scale (ground truth over estimate: above 1, the estimate is too short).
    const eval::AteResult ate_sim3 = eval::ComputeAte(est_, gt, true);
    json->Set("ate.sim3_rmse_m", ate_sim3.ate.rmse);
    json->Set("ate.sim3_scale", ate_sim3.alignment.scale);
    if (path_length_m > 0) json->Set("ate.rmse_pct_path", 100.0 * ate.ate.rmse / path_length_m);
    json->Set("rpe.trans_rmse_m", rpe.rmse);
    json->Set("rpe.delta_frames", 1);
    s.has_ate = true;
    s.ate_rmse_m = ate.ate.rmse;
    s.ate_pct_path = path_length_m > 0 ? 100.0 * ate.ate.rmse / path_length_m : 0;
    s.rpe_rmse_m = rpe.rmse;
  } catch (const InputError& e) {
    s.ate_unavailable = std::string("the estimate cannot be aligned with the ground truth: ") + e.what();
    json->Set("ate.unavailable", s.ate_unavailable);
  }
  return s;
}

std::string SlamSummaryLine(const SlamSummary& s) {
  char buf[256];
  if (s.has_ate) {
    std::snprintf(buf, sizeof buf, "ATE %.4f m RMSE (%.2f%% of path), ", s.ate_rmse_m, s.ate_pct_path);
  } else {
    buf[0] = 0;
  }
  std::string out = buf;
  if (!s.ate_unavailable.empty()) out += "no ATE (" + s.ate_unavailable + "), ";
  std::snprintf(buf, sizeof buf, "%d lost of %d frames, %d keyframes, %d map points, tracking %.1f ms median (p95 %.1f)",
                s.lost, s.frames, s.keyframes, s.map_points, s.track_ms_median, s.track_ms_p95);
  return out + buf;
}

}  // namespace viqu::runner

#include "runner/metric_keys.h"

#include <algorithm>

namespace viqu::runner {

const std::vector<std::string>& MetricKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k = {
        // the run (run_metrics.cc) and the replay (apps/slam_command.cc)
        "scenario", "seed", "sim_time_s", "path_length_m", "robot.fell", "robot.fell_at_s", "robot.steer_source", "camera.frames",
        "dataset", "camera.frames_skipped", "format", "masks", "camera.calibration", "camera.fx", "camera.fy",
        "camera.cx", "camera.cy", "camera.width", "camera.height",
        // SLAM (slam_run.cc)
        "slam.mode", "slam.input", "slam.mapping_mode", "slam.dynamic_method", "slam.settings_file",
        "ate.rmse_m", "ate.mean_m", "ate.median_m", "ate.std_m", "ate.min_m", "ate.max_m", "ate.pairs",
        "ate.rmse_pct_path", "ate.sim3_rmse_m", "ate.sim3_scale", "ate.unavailable", "rpe.trans_rmse_m",
        "rpe.delta_frames", "tracking.frames", "tracking.lost_frames", "tracking.keyframes", "tracking.map_points",
        "tracking.relocalisations", "tracking.keyframes_freed", "tracking.map_points_freed",
        "tracking.map_points_held", "tracking.map_heap_mb", "tracking.object_points_erased",
        "tracking.object_points_retired", "tracking.prior_frames_external", "tracking.prior_err_mm_median",
        "tracking.prior_err_mm_p95", "tracking.prior_err_deg_median", "tracking.prior_err_deg_p95",
        "tracking.search_px_median", "imu.gyro_prior", "imu.gyro_priors_given",
        "timing.track_ms_median", "timing.track_ms_p95", "timing.dynamic_ms_median", "timing.dynamic_ms_p95",
        "timing.local_ba_count", "timing.local_ba_ms_median", "timing.render_ms_median", "timing.render_ms_p95",
        "timing.renderer", "timing.real_time_factor", "timing.wall_time_s",
        // dynamic objects (dynamic_score.cc; its list dynamic.objects is no single value)
        "dynamic.precision", "dynamic.recall", "dynamic.latency_s_median", "dynamic.latency_s_max",
        "dynamic.kept_on_static_movables", "dynamic.dropped_on_moving", "dynamic.decided_dynamic_share",
        "dynamic.object_frames", "dynamic.scored_object_frames",
        // leg odometry, fusion and slip (lo_run.cc, slip_score.cc)
        "lo.ate.rmse_m", "lo.drift_pct_path", "lo.final_error_m", "lo.yaw_drift_deg", "lo.update_ms_mean",
        "lo.fused", "lo.frames_carried", "lo.fusion_corrections", "lo.fusion_bias_updates", "lo.levellings",
        "lo.gyro_bias_z_radps", "lo.true_gyro_bias_z_radps", "lo.yaw_bias_pieces", "lo.yaw_bias_rejected",
        "lo.yaw_bias_turning", "slip.precision", "slip.recall", "slip.events", "slip.truth_events",
        "slip.fused.precision", "slip.fused.recall", "slip.fused.events",
        // issue 55's slip, contact and foot-force scoring (slip_score.cc, contact_score.cc)
        "slip.recall_by_travel.3_10mm", "slip.truth_events_by_travel.3_10mm", "slip.recall_by_travel.10_30mm", "slip.truth_events_by_travel.10_30mm", "slip.recall_by_travel.over_30mm", "slip.truth_events_by_travel.over_30mm", "slip.latency_ms_median", "slip.false_per_m", "slip.fused.recall_by_travel.3_10mm", "slip.fused.truth_events_by_travel.3_10mm", "slip.fused.recall_by_travel.10_30mm", "slip.fused.truth_events_by_travel.10_30mm", "slip.fused.recall_by_travel.over_30mm", "slip.fused.truth_events_by_travel.over_30mm", "slip.fused.latency_ms_median", "slip.fused.false_per_m", "slip.fused.truth_events", "slip.truth_travel_m", "slip.contact_debounce_s", "slip.match_window_s", "contact.accuracy", "contact.samples", "contact.touchdown_err_ms_median", "contact.liftoff_err_ms_median", "contact.touchdowns", "contact.touchdowns_paired", "contact.liftoffs", "contact.liftoffs_paired", "grf.normal_rmse_n", "grf.true_normal_mean_n", "grf.normal_rmse_pct", "grf.samples", "slip.oracle.precision", "slip.oracle.recall", "slip.oracle.events", "slip.oracle.truth_events", "slip.oracle.latency_ms_median", "slip.oracle.false_per_m", "slip.oracle.recall_by_travel.3_10mm", "slip.oracle.truth_events_by_travel.3_10mm", "slip.oracle.recall_by_travel.10_30mm", "slip.oracle.truth_events_by_travel.10_30mm", "slip.oracle.recall_by_travel.over_30mm", "slip.oracle.truth_events_by_travel.over_30mm", "slip.gate.precision", "slip.gate.recall", "slip.gate.events", "slip.gate.truth_events", "slip.gate.latency_ms_median", "slip.gate.false_per_m", "slip.gate.recall_by_travel.3_10mm", "slip.gate.truth_events_by_travel.3_10mm", "slip.gate.recall_by_travel.10_30mm", "slip.gate.truth_events_by_travel.10_30mm", "slip.gate.recall_by_travel.over_30mm", "slip.gate.truth_events_by_travel.over_30mm"};
    std::sort(k.begin(), k.end());
    return k;
  }();
  return keys;
}

bool IsMetricKey(const std::string& key) {
  const std::vector<std::string>& k = MetricKeys();
  return std::binary_search(k.begin(), k.end(), key);
}

namespace {

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string NearestMetricKey(const std::string& key) {
  std::string best;
  size_t best_d = 0;
  for (const std::string& k : MetricKeys()) {
    const size_t d = EditDistance(key, k);
    if (best.empty() || d < best_d) best = k, best_d = d;
  }
  return best_d <= key.size() / 3 ? best : "";
}

}  // namespace viqu::runner

#include "runner/lo_run.h"

#include <cmath>
#include <cstdio>

#include "common/atomic_file.h"
#include "slam/eval/trajectory_error.h"

namespace viqu::runner {

LoRun::LoRun(const slam::LegOdometrySettings& settings, const kin::LegKinematics& kin, const std::string& out_dir,
             int64_t t0_ns, const Eigen::Isometry3d& T_w_body0, const Eigen::Isometry3d& T_body_cam)
    : lo_(settings, kin),
      T_body_cam_(T_body_cam),
      out_dir_(out_dir),
      writer_(out_dir + "/trajectory_lo.txt"),
      log_(std::make_unique<AtomicOutputFile>(out_dir + "/lo.csv")) {
  lo_.Start(t0_ns, T_w_body0);
  std::string header = "t_s,x,y,z,vx,vy,vz,true_x,true_y,true_z,true_vx,true_vy,true_vz";
  for (int i = 0; i < kNumLegs; ++i) {
    const std::string n = LegName(static_cast<Leg>(i));
    header += "," + n + "_contact," + n + "_slip," + n + "_m2," + n + "_true_contact," + n + "_sole_speed";
  }
  log_->Write(header + "\n");
}

void LoRun::AddJoints(const JointState& js, int64_t period_ns, const LoTruth& truth) {
  lo_.AddJoints(js);
  true_gyro_bias_i_ = truth.gyro_bias_i;
  const Eigen::Vector3d p = lo_.filter().position(), v = lo_.filter().velocity();
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f",
                sim::FormatSeconds(js.t_ns).c_str(), p.x(), p.y(), p.z(), v.x(), v.y(), v.z(), truth.p_w_body.x(),
                truth.p_w_body.y(), truth.p_w_body.z(), truth.vel_w_body.x(), truth.vel_w_body.y(), truth.vel_w_body.z());
  std::string line = buf;
  for (int i = 0; i < kNumLegs; ++i) {
    const lo::FootStatus& f = lo_.feet()[i];
    std::snprintf(buf, sizeof buf, ",%d,%d,%.3g,%d,%.4f", f.contact ? 1 : 0, f.slipping ? 1 : 0, f.mahalanobis2,
                  truth.contact[i] ? 1 : 0, truth.sole_speed_mps[i]);
    line += buf;
  }
  log_->Write(line + "\n");
  std::array<bool, kNumLegs> true_slip{}, detected{};
  std::array<double, kNumLegs> m2{};
  for (int i = 0; i < kNumLegs; ++i) {
    true_slip[i] = truth.contact[i] && truth.sole_speed_mps[i] > kSlipSpeedMps;
    detected[i] = lo_.feet()[i].slipping;
    m2[i] = lo_.feet()[i].mahalanobis2;
  }
  truth_events_.Add(js.t_ns, period_ns, true_slip, truth.sole_speed_mps);
  detected_events_.Add(js.t_ns, period_ns, detected, m2);
  if (fused_) {
    for (int i = 0; i < kNumLegs; ++i) {
      detected[i] = fused_->feet()[i].slipping;
      m2[i] = fused_->feet()[i].mahalanobis2;
    }
    fused_events_.Add(js.t_ns, period_ns, detected, m2);
  }
}

void LoRun::AddFrame(int64_t t_ns) {
  const StampedPose p = ToStampedPose(t_ns, lo_.T_w_body() * T_body_cam_);
  writer_.Add(p);
  est_.push_back(p);
}

LoSummary LoRun::Finish(const eval::Trajectory& gt_cam, double path_length_m, JsonWriter* json) {
  writer_.Close();
  log_->Commit();
  LoSummary s;
  std::vector<SlipEvent> truth = truth_events_.Finish();
  std::vector<SlipEvent> detected = detected_events_.Finish();
  if (fused_) {
    std::vector<SlipEvent> truth_copy = truth;  // ScoreSlip marks the matches in place
    std::vector<SlipEvent> fused = fused_events_.Finish();
    s.slip_fused = ScoreSlip(&truth_copy, &fused, kSlipMatchToleranceS);
  }
  s.slip = ScoreSlip(&truth, &detected, kSlipMatchToleranceS);
  WriteFileAtomic(out_dir_ + "/slip.csv", SlipCsv(truth, detected));
  s.update_ms_mean = lo_.mean_update_ms();
  if (!gt_cam.empty() && est_.size() >= 3) {
    const eval::AteResult ate = eval::ComputeAte(est_, gt_cam);
    s.ate_rmse_m = ate.ate.rmse;
    // Drift: the final position error after aligning the first pose (no fit over the run).
    const Eigen::Isometry3d T_align = ToIsometry(gt_cam.front()) * ToIsometry(est_.front()).inverse();
    const Eigen::Isometry3d est_end = T_align * ToIsometry(est_.back());
    const Eigen::Isometry3d gt_end = ToIsometry(gt_cam.back());
    const double err = (est_end.translation() - gt_end.translation()).norm();
    s.drift_pct_path = path_length_m > 0 ? 100.0 * err / path_length_m : 0;
    // Yaw drift: the heading of the camera's forward axis (optical z) in the horizontal plane.
    const Eigen::Vector3d f_est = est_end.linear().col(2), f_gt = gt_end.linear().col(2);
    s.yaw_drift_deg = std::remainder(std::atan2(f_est.y(), f_est.x()) - std::atan2(f_gt.y(), f_gt.x()), 2 * M_PI) * 180 / M_PI;
    json->Set("lo.ate.rmse_m", s.ate_rmse_m);
    json->Set("lo.drift_pct_path", s.drift_pct_path);
    json->Set("lo.final_error_m", err);
    json->Set("lo.yaw_drift_deg", s.yaw_drift_deg);
  }
  json->Set("lo.update_ms_mean", s.update_ms_mean);
  // The gyro bias about the trunk's vertical: the estimate at the end (stance pairs) and the truth.
  json->Set("lo.gyro_bias_z_radps", lo_.attitude().gyro_bias().z());
  json->SetNumbers("lo.true_gyro_bias_radps", {true_gyro_bias_i_.x(), true_gyro_bias_i_.y(), true_gyro_bias_i_.z()});
  json->Set("lo.true_gyro_bias_z_radps", true_gyro_bias_i_.z());
  json->Set("lo.yaw_bias_pieces", lo_.yaw_bias().pieces());
  json->Set("lo.yaw_bias_rejected", lo_.yaw_bias().rejected());
  json->Set("lo.yaw_bias_turning", lo_.yaw_bias().turning());
  json->Set("slip.precision", s.slip.precision);
  json->Set("slip.recall", s.slip.recall);
  json->Set("slip.events", s.slip.detected_events);
  json->Set("slip.truth_events", s.slip.truth_events);
  if (s.slip_fused) {
    json->Set("slip.fused.precision", s.slip_fused->precision);
    json->Set("slip.fused.recall", s.slip_fused->recall);
    json->Set("slip.fused.events", s.slip_fused->detected_events);
  }
  return s;
}

std::string LoSummaryLine(const LoSummary& s) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "LO: ATE %.4f m RMSE, drift %.2f%% of path, yaw drift %.1f deg; slip precision %.2f recall %.2f "
                "(%d true events, %d detected); %.3f ms per IMU+encoder sample",
                s.ate_rmse_m, s.drift_pct_path, s.yaw_drift_deg, s.slip.precision, s.slip.recall, s.slip.truth_events,
                s.slip.detected_events, s.update_ms_mean);
  std::string line = buf;
  if (s.slip_fused) {
    std::snprintf(buf, sizeof buf, "; fused with vision: slip precision %.2f recall %.2f (%d detected)",
                  s.slip_fused->precision, s.slip_fused->recall, s.slip_fused->detected_events);
    line += buf;
  }
  return line;
}

}  // namespace viqu::runner

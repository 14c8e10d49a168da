#include "runner/lo_run.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "common/atomic_file.h"
#include "slam/eval/trajectory_error.h"

namespace viqu::runner {

LoRun::LoRun(const slam::LegOdometrySettings& settings, const kin::LegKinematics& kin, const std::string& out_dir,
             int64_t t0_ns, const Eigen::Isometry3d& T_w_body0, const Eigen::Isometry3d& T_body_cam)
    : lo_(settings, kin),
      T_body_cam_(T_body_cam),
      out_dir_(out_dir),
      writer_(out_dir + "/trajectory_lo.txt"),
      log_(std::make_unique<AtomicOutputFile>(out_dir + "/lo.csv")),
      oracle_(kin, settings.slip_travel_m),
      forces_(kin, lo::FootForceModel{}, lo::ForceAlignment::kCentred) {
  lo_.Start(t0_ns, T_w_body0);
  std::string header = "t_s,x,y,z,vx,vy,vz,true_x,true_y,true_z,true_vx,true_vy,true_vz";
  for (int i = 0; i < kNumLegs; ++i) {
    const std::string n = LegName(static_cast<Leg>(i));
    header += "," + n + "_contact," + n + "_slip," + n + "_m2," + n + "_true_contact," + n + "_sole_speed," + n +
              "_true_travel," + n + "_normal_n," + n + "_true_normal_n," + n + "_travel," + n + "_slipped";
  }
  log_->Write(header + "\n");
}

void LoRun::AddJoints(const JointState& js, int64_t period_ns, const LoTruth& truth) {
  lo_.AddJoints(js);
  true_gyro_bias_i_ = truth.gyro_bias_i;
  // The foot forces from the torques, with the attitude's gravity; their vertical part is the
  // normal force on flat ground (on a slope it is the normal force's vertical share).
  const Eigen::Matrix3d R = lo_.attitude().q_w_b().toRotationMatrix();
  const lo::FootForces f = forces_.Update(js, R.transpose() * Eigen::Vector3d(0, 0, -9.81));
  std::array<double, kNumLegs> est_normal;
  for (int i = 0; i < kNumLegs; ++i) {
    est_normal[i] = f.valid[i] ? (R * f.f_trunk[i]).z() : std::numeric_limits<double>::quiet_NaN();
  }
  Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();
  T_true.linear() = truth.q_w_body.normalized().toRotationMatrix();
  T_true.translation() = truth.p_w_body;
  oracle_.Add(js, T_true, truth.w_body, truth.contact);
  const Eigen::Vector3d p = lo_.filter().position(), v = lo_.filter().velocity();
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f",
                sim::FormatSeconds(js.t_ns).c_str(), p.x(), p.y(), p.z(), v.x(), v.y(), v.z(), truth.p_w_body.x(),
                truth.p_w_body.y(), truth.p_w_body.z(), truth.vel_w_body.x(), truth.vel_w_body.y(), truth.vel_w_body.z());
  std::string line = buf;
  std::array<bool, kNumLegs> contact{}, detected{}, gated{};
  std::array<double, kNumLegs> m2{}, travel{};
  for (int i = 0; i < kNumLegs; ++i) {
    const lo::FootStatus& foot = lo_.feet()[i];
    std::snprintf(buf, sizeof buf, ",%d,%d,%.3g,%d,%.4f,%.4f,%.2f,%.2f,%.4f,%d", foot.contact ? 1 : 0,
                  foot.slipping ? 1 : 0, foot.mahalanobis2, truth.contact[i] ? 1 : 0, truth.sole_speed_mps[i],
                  truth.travel_m[i], est_normal[i], truth.normal_force_n[i], foot.travel_m, foot.slipped ? 1 : 0);
    line += buf;
    contact[i] = foot.contact;
    detected[i] = foot.slipped;
    gated[i] = foot.slipping;
    m2[i] = foot.mahalanobis2;
    travel[i] = foot.travel_m;
  }
  log_->Write(line + "\n");
  detected_events_.Add(js.t_ns, period_ns, contact, detected, travel);
  gate_events_.Add(js.t_ns, period_ns, contact, gated, m2);
  oracle_events_.Add(js.t_ns, period_ns, truth.contact, oracle_.slipped(), oracle_.travel_m());
  contact_score_.Add(js.t_ns, contact, truth.contact);
  if (f.t_ns == js.t_ns) {
    contact_score_.AddForce(est_normal, truth.contact, truth.normal_force_n);
  } else if (f.t_ns == last_truth_ns_) {
    contact_score_.AddForce(est_normal, last_true_contact_, last_true_normal_n_);
  }
  last_truth_ns_ = js.t_ns;
  last_true_contact_ = truth.contact;
  last_true_normal_n_ = truth.normal_force_n;
  if (fused_) {
    for (int i = 0; i < kNumLegs; ++i) {
      contact[i] = fused_->feet()[i].contact;
      detected[i] = fused_->feet()[i].slipped;
      travel[i] = fused_->feet()[i].travel_m;
    }
    fused_events_.Add(js.t_ns, period_ns, contact, detected, travel);
  }
}

void LoRun::AddFrame(int64_t t_ns) {
  const StampedPose p = ToStampedPose(t_ns, lo_.T_w_body() * T_body_cam_);
  writer_.Add(p);
  est_.push_back(p);
}

LoSummary LoRun::Finish(const eval::Trajectory& gt_cam, double path_length_m, const std::vector<TrueStance>& stances,
                        const ScoringConfig& scoring, JsonWriter* json) {
  writer_.Close();
  log_->Commit();
  LoSummary s;
  SlipScoreOptions opt;
  opt.match_before_s = scoring.slip_match_before_s;
  opt.match_after_s = scoring.slip_match_after_s;
  opt.path_length_m = path_length_m;
  std::vector<SlipEvent> truth = TrueSlipEvents(stances);
  std::vector<SlipEvent> detected = detected_events_.Finish();
  if (fused_) {
    std::vector<SlipEvent> truth_copy = truth;  // ScoreSlip marks the matches in place
    std::vector<SlipEvent> fused = fused_events_.Finish();
    s.slip_fused = ScoreSlip(&truth_copy, &fused, opt);
  }
  {
    std::vector<SlipEvent> truth_copy = truth;
    std::vector<SlipEvent> gate = gate_events_.Finish();
    s.slip_gate = ScoreSlip(&truth_copy, &gate, opt);
    truth_copy = truth;
    std::vector<SlipEvent> oracle = oracle_events_.Finish();
    s.slip_oracle = ScoreSlip(&truth_copy, &oracle, opt);
  }
  s.slip = ScoreSlip(&truth, &detected, opt);
  WriteFileAtomic(out_dir_ + "/slip.csv", SlipCsv(truth, detected));
  std::string contact_csv;
  s.contact = contact_score_.Finish(stances, &contact_csv);
  WriteFileAtomic(out_dir_ + "/contact.csv", contact_csv);
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
  const auto slip_keys = [json](const std::string& prefix, const SlipScore& score) {
    json->Set(prefix + "precision", score.precision);
    json->Set(prefix + "recall", score.recall);
    json->Set(prefix + "events", score.detected_events);
    json->Set(prefix + "truth_events", score.truth_events);
    for (int b = 0; b < 3; ++b) {
      json->Set(prefix + "recall_by_travel." + kTravelBandNames[b], score.recall_in_band(b));
      json->Set(prefix + "truth_events_by_travel." + kTravelBandNames[b], score.band_events[b]);
    }
    json->Set(prefix + "latency_ms_median", score.latency_ms_median);
    json->Set(prefix + "false_per_m", score.false_per_m);
  };
  slip_keys("slip.", s.slip);
  if (s.slip_fused) slip_keys("slip.fused.", *s.slip_fused);
  slip_keys("slip.gate.", s.slip_gate);
  slip_keys("slip.oracle.", s.slip_oracle);
  // The definitions the slip figures were scored with (the scenario's scoring block).
  json->Set("slip.truth_travel_m", scoring.slip_travel_m);
  json->Set("slip.contact_debounce_s", scoring.contact_debounce_s);
  json->SetNumbers("slip.match_window_s", {-scoring.slip_match_before_s, scoring.slip_match_after_s});
  json->Set("contact.accuracy", s.contact.accuracy);
  json->Set("contact.samples", static_cast<int64_t>(s.contact.samples));
  json->Set("contact.touchdown_err_ms_median", s.contact.touchdown_err_ms_median);
  json->Set("contact.liftoff_err_ms_median", s.contact.liftoff_err_ms_median);
  json->Set("contact.touchdowns", s.contact.touchdowns);
  json->Set("contact.touchdowns_paired", s.contact.touchdowns_paired);
  json->Set("contact.liftoffs", s.contact.liftoffs);
  json->Set("contact.liftoffs_paired", s.contact.liftoffs_paired);
  json->Set("grf.normal_rmse_n", s.contact.normal_rmse_n);
  json->Set("grf.true_normal_mean_n", s.contact.true_normal_mean_n);
  json->Set("grf.normal_rmse_pct", 100 * s.contact.normal_rmse_n / s.contact.true_normal_mean_n);
  json->Set("grf.samples", static_cast<int64_t>(s.contact.force_samples));
  return s;
}

std::string LoSummaryLine(const LoSummary& s) {
  char buf[560];
  std::snprintf(buf, sizeof buf, "LO: ATE %.4f m RMSE, drift %.2f%% of path, yaw drift %.1f deg; %.3f ms per IMU+encoder sample\n",
                s.ate_rmse_m, s.drift_pct_path, s.yaw_drift_deg, s.update_ms_mean);
  std::string line = buf;
  std::snprintf(buf, sizeof buf,
                "slip: precision %.2f recall %.2f (%d true events, %d detected), %.1f false per m, latency median %.0f ms; "
                "contact %.1f%% of samples, touch-down %.1f ms; foot normal force RMSE %.2f N (%.0f%% of the mean)",
                s.slip.precision, s.slip.recall, s.slip.truth_events, s.slip.detected_events, s.slip.false_per_m,
                s.slip.latency_ms_median, 100 * s.contact.accuracy, s.contact.touchdown_err_ms_median,
                s.contact.normal_rmse_n, 100 * s.contact.normal_rmse_n / s.contact.true_normal_mean_n);
  line += buf;
  std::snprintf(buf, sizeof buf,
                "; the velocity gates' flags: precision %.2f recall %.2f (%d detected); on the true motion and contact "
                "(oracle): precision %.2f recall %.2f (%d detected)",
                s.slip_gate.precision, s.slip_gate.recall, s.slip_gate.detected_events, s.slip_oracle.precision,
                s.slip_oracle.recall, s.slip_oracle.detected_events);
  line += buf;
  if (s.slip_fused) {
    std::snprintf(buf, sizeof buf, "; fused with vision: slip precision %.2f recall %.2f (%d detected)",
                  s.slip_fused->precision, s.slip_fused->recall, s.slip_fused->detected_events);
    line += buf;
  }
  return line;
}

}  // namespace viqu::runner

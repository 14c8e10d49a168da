#pragma once
// The leg-odometry/IMU estimator over one run, live: feeds it the IMU, the encoders and the
// contact readings, writes trajectory_lo.txt (left camera in the world, one line per camera
// frame, like trajectory_est.txt), scores its slip decisions, contact and foot forces against the
// simulator's truth (slip.csv, contact.csv; runner/slip_score.h, runner/contact_score.h), logs
// every encoder sample to lo.csv (estimate, truth, and per foot the contact, the gates' flag and
// statistic, the true contact, sole speed and stance travel, the estimated normal force (of the
// reading before: centred, slam/lo/foot_force.h) and the true one, the estimated stance travel and
// the slip decision) and adds the lo.*, slip.*, contact.* and grf.* keys to metrics.json.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include "runner/contact_score.h"
#include "runner/foot_truth.h"
#include "runner/slip_oracle.h"
#include "runner/slip_score.h"
#include "scenario/scenario.h"
#include "common/atomic_output_file.h"
#include "common/json_writer.h"
#include "kinematics/leg_kinematics.h"
#include "sim/trajectory_writer.h"
#include "slam/eval/trajectory.h"
#include "slam/lo/foot_force.h"
#include "slam/lo/leg_odometry.h"

namespace viqu::runner {

// What the simulator knows at one encoder sample (metrics only).
struct LoTruth {
  std::array<bool, kNumLegs> contact{};           // debounced (runner/foot_truth.h)
  std::array<double, kNumLegs> sole_speed_mps{};  // speed of the sole's material point (m/s)
  std::array<double, kNumLegs> travel_m{};        // the stance's net travel so far (m)
  std::array<double, kNumLegs> normal_force_n{};  // the ground's normal force on each foot (N)
  Eigen::Vector3d p_w_body = Eigen::Vector3d::Zero();    // trunk position (m)
  Eigen::Quaterniond q_w_body = Eigen::Quaterniond::Identity();  // trunk orientation
  Eigen::Vector3d w_body = Eigen::Vector3d::Zero();       // trunk rate (rad/s, trunk frame)
  Eigen::Vector3d vel_w_body = Eigen::Vector3d::Zero();  // trunk velocity (m/s)
  Eigen::Vector3d gyro_bias_i = Eigen::Vector3d::Zero();  // the simulated gyro's bias now (rad/s, IMU frame)
};

struct LoSummary {
  double ate_rmse_m = 0, drift_pct_path = 0, yaw_drift_deg = 0;
  SlipScore slip;       // the reported slip decision (lo.slip_travel_m)
  SlipScore slip_gate;  // the filter's velocity gates' flags, scored the same way (slip.gate.*)
  SlipScore slip_oracle;  // the slip by travel on the true trunk motion and contact (slip.oracle.*)
  ContactScore contact;
  std::optional<SlipScore> slip_fused;  // the fused filter's decisions (mode full)
  double update_ms_mean = 0;
};

class LoRun {
 public:
  // Anchored at the true first trunk pose at t0_ns (as the SLAM map is at the first camera pose).
  LoRun(const slam::LegOdometrySettings& settings, const kin::LegKinematics& kin, const std::string& out_dir,
        int64_t t0_ns, const Eigen::Isometry3d& T_w_body0, const Eigen::Isometry3d& T_body_cam);

  // The filter fused with vision (mode full), whose slip decisions are scored too (slip.fused.*):
  // it must have taken each encoder reading before AddJoints() is called with it.
  void SetFused(const lo::LegOdometry* fused) { fused_ = fused; }

  void AddImu(const ImuSample& s) { lo_.AddImu(s); }
  void AddContact(const ContactReading& c) { lo_.AddContact(c); }
  void AddJoints(const JointState& js, int64_t period_ns, const LoTruth& truth);
  // Writes the estimate at a camera frame's time.
  void AddFrame(int64_t t_ns);

  // `stances`: the true stances of the run (FootTruth::Finish); `scoring` the scenario's.
  LoSummary Finish(const eval::Trajectory& gt_cam, double path_length_m, const std::vector<TrueStance>& stances,
                   const ScoringConfig& scoring, JsonWriter* json);

  // The leg-odometry estimate of the left camera so far (one pose per camera frame).
  const eval::Trajectory& estimate() const { return est_; }

 private:
  lo::LegOdometry lo_;
  Eigen::Isometry3d T_body_cam_;
  std::string out_dir_;
  sim::TrajectoryWriter writer_;
  std::unique_ptr<AtomicOutputFile> log_;  // lo.csv
  eval::Trajectory est_;
  SlipDetectionBuilder detected_events_;
  SlipDetectionBuilder gate_events_;
  SlipOracle oracle_;
  SlipDetectionBuilder oracle_events_;
  const lo::LegOdometry* fused_ = nullptr;
  SlipDetectionBuilder fused_events_;
  lo::FootForceEstimator forces_;  // foot forces from the torques, scored against the simulator's
  ContactScorer contact_score_;
  // The truth at the previous encoder reading, for a force estimate dated there (centred).
  int64_t last_truth_ns_ = -1;
  std::array<bool, kNumLegs> last_true_contact_{};
  std::array<double, kNumLegs> last_true_normal_n_{};
  Eigen::Vector3d true_gyro_bias_i_ = Eigen::Vector3d::Zero();  // at the last encoder reading
};

// "LO: ATE 0.0123 m RMSE, drift 1.23% of path, yaw drift 2.1 deg; ..." and a second line with
// slip, contact and foot force.
std::string LoSummaryLine(const LoSummary& s);

}  // namespace viqu::runner

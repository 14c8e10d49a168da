#pragma once
// The leg-odometry/IMU estimator over one run, live: feeds it the IMU, the encoders and the
// contact readings, writes trajectory_lo.txt (left camera in the world, one line per camera
// frame, like trajectory_est.txt), scores its slip decisions against the simulator's truth
// (slip.csv), logs every encoder sample to lo.csv (estimate, truth, and per foot the contact,
// slip flag and gate statistic) and adds the lo.* and slip.* keys to metrics.json.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include "runner/slip_score.h"
#include "common/atomic_output_file.h"
#include "common/json_writer.h"
#include "kinematics/leg_kinematics.h"
#include "sim/trajectory_writer.h"
#include "slam/eval/trajectory.h"
#include "slam/lo/leg_odometry.h"

namespace viqu::runner {

// What the simulator knows at one encoder sample (metrics only).
struct LoTruth {
  std::array<bool, kNumLegs> contact{};
  std::array<double, kNumLegs> sole_speed_mps{};  // speed of the sole's material point (m/s)
  Eigen::Vector3d p_w_body = Eigen::Vector3d::Zero();    // trunk position (m)
  Eigen::Vector3d vel_w_body = Eigen::Vector3d::Zero();  // trunk velocity (m/s)
  Eigen::Vector3d gyro_bias_i = Eigen::Vector3d::Zero();  // the simulated gyro's bias now (rad/s, IMU frame)
};

struct LoSummary {
  double ate_rmse_m = 0, drift_pct_path = 0, yaw_drift_deg = 0;
  SlipScore slip;
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

  LoSummary Finish(const eval::Trajectory& gt_cam, double path_length_m, JsonWriter* json);

  // The leg-odometry estimate of the left camera so far (one pose per camera frame).
  const eval::Trajectory& estimate() const { return est_; }

 private:
  lo::LegOdometry lo_;
  Eigen::Isometry3d T_body_cam_;
  std::string out_dir_;
  sim::TrajectoryWriter writer_;
  std::unique_ptr<AtomicOutputFile> log_;  // lo.csv
  eval::Trajectory est_;
  SlipEventBuilder truth_events_{kSlipMinDurationS};
  SlipEventBuilder detected_events_{0.0};
  const lo::LegOdometry* fused_ = nullptr;
  SlipEventBuilder fused_events_{0.0};
  Eigen::Vector3d true_gyro_bias_i_ = Eigen::Vector3d::Zero();  // at the last encoder reading
};

// "LO: ATE 0.0123 m, drift 1.23% of path, yaw drift 2.1 deg; slip precision 0.90 recall 0.85 (20 true, 19 detected)"
std::string LoSummaryLine(const LoSummary& s);

}  // namespace viqu::runner

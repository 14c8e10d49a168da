#pragma once
// Leg odometry with the IMU (paper eqs. 5-7): the attitude filter, the linear Kalman filter of
// eq. 5, contact from the configured source, the slip gate, and the gyro bias about the vertical
// from pairs of stance feet (yaw_bias_from_feet.h). Inputs are the measurement
// structs only (IMU samples, encoder readings, contact readings); the leg kinematics come from
// the URDF through kinematics/. JointState::contact is simulator truth and is never read here.
#include <array>
#include <cstdint>
#include <deque>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/leg_kinematics.h"
#include "slam/lo/attitude_filter.h"
#include "slam/lo/gravity_tilt.h"
#include "slam/lo/leg_imu_kf.h"
#include "slam/lo/yaw_bias_from_feet.h"
#include "slam/measurements/contact_reading.h"
#include "slam/measurements/ground_truth_pose.h"
#include "slam/measurements/imu_sample.h"
#include "slam/measurements/joint_state.h"
#include "slam/settings/slam_settings.h"

namespace viqu::lo {

// The attitude filter's options from the settings' attitude_* keys (standard gravity).
AttitudeFilterOptions AttitudeOptionsOf(const slam::LegOdometrySettings& s);

// What the estimator concluded about one foot at the last encoder reading.
struct FootStatus {
  bool contact = false;          // in contact by the configured source
  bool slipping = false;         // in contact, but its velocity failed a slip gate (chi-square or speed)
  double mahalanobis2 = 0;       // squared Mahalanobis distance of its velocity innovation (0 in swing and settling)
  int64_t touchdown_ns = 0;      // time of its last touch-down (ns)
  // The reported slip decision (lo.slip_travel_m): the horizontal travel of its contact point since
  // lo.slip_travel_from_s after its touch-down, against the body's predicted travel (m, 0 before), and
  // whether it has exceeded the threshold in this stance (held until lift-off).
  double travel_m = 0;
  bool slipped = false;
};

class LegOdometry {
 public:
  // Throws InputError for an unknown contact source.
  LegOdometry(const slam::LegOdometrySettings& settings, const kin::LegKinematics& kin);

  // Anchors the estimate: body pose in the world at t_ns, at rest. The feet start where the
  // kinematics of the first encoder reading put them.
  void Start(int64_t t_ns, const Eigen::Isometry3d& T_w_body);

  // One IMU sample: attitude update, then the filter's prediction up to its time.
  void AddImu(const ImuSample& s);
  // Planned stance or touch sensors (contact: schedule | touch); ignored for estimated contact.
  void AddContact(const ContactReading& c);
  // One encoder reading: the filter's update with every foot's kinematics.
  void AddJoints(const JointState& js);

  // A pose from elsewhere (the visual estimate, slam.mode full) replaces the estimate: the
  // position moves the body and the feet together, the orientation replaces the attitude's, but
  // levelled to the IMU's mean force when its "up" is further from it than lo.fusion_tilt_gate_deg
  // (returns true then). With lo.fusion_gyro_bias_s, two corrections in a row (nothing levelled,
  // nothing carried between) also correct the gyro bias: the rotation from the attitude's
  // gyro-integrated orientation to vision's is the bias left over the interval.
  bool CorrectPose(const Eigen::Isometry3d& T_w_body);
  // The same check on the filter's own orientation (slam.mode full, while it carries the pose)
  // with lo.fusion_tilt_carry_gate_deg: the attitude filter's own gravity correction leans with
  // the gait (up to 2.6 deg while walking), the mean force does not; true if it levelled.
  bool KeepLevel();
  // Vision did not correct this frame (slam.mode full): the attitude's gravity correction resumes,
  // and the next correction starts a new interval for the gyro bias.
  void Carried() {
    vision_reference_ns_.reset();
    HoldGravity(false);
  }
  // Holds the attitude's gravity correction (lo.fusion_hold_gravity, while vision corrects the
  // filter every frame) or releases it; a no-op when that setting is off.
  void HoldGravity(bool hold) { attitude_.HoldGravity(hold && settings_.fusion_hold_gravity); }

  bool started() const { return started_; }
  // Time of the last IMU sample taken in (ns; 0 before any).
  int64_t t_ns() const { return last_imu_ns_.value_or(0); }
  Eigen::Isometry3d T_w_body() const;   // current estimate of the trunk (IMU) pose
  Eigen::Vector3d velocity() const { return kf_.velocity(); }
  const std::array<FootStatus, kNumLegs>& feet() const { return feet_; }
  const LegImuKf& filter() const { return kf_; }
  const AttitudeFilter& attitude() const { return attitude_; }
  const YawBiasFromFeet& yaw_bias() const { return yaw_bias_; }
  int levellings() const { return levellings_; }  // orientations levelled by the tilt gate so far
  int vision_bias_updates() const { return vision_bias_updates_; }  // gyro bias corrections from vision so far
  // Mean time of one AddImu + AddJoints pair so far (ms), for the run summary.
  double mean_update_ms() const { return updates_ ? update_ms_sum_ / updates_ : 0.0; }

 private:
  std::array<bool, kNumLegs> ContactOf(const std::array<Eigen::Vector3d, kNumLegs>& rel_w) const;
  // R levelled when its "up" is further than gate_deg from the IMU's mean force, or nothing when
  // it passes (or the gate is 0, or a whole window has not been seen yet).
  std::optional<Eigen::Matrix3d> Levelled(const Eigen::Matrix3d& R, double gate_deg) const;
  // Replaces the attitude's orientation, telling the stance-pair yaw-bias estimator the turn.
  void SetOrientation(const Eigen::Matrix3d& R_w_b);

  slam::LegOdometrySettings settings_;
  const kin::LegKinematics& kin_;
  AttitudeFilter attitude_;
  LegImuKf kf_;
  bool estimated_contact_ = false;  // lo.contact is estimated (the others come through AddContact)
  bool slip_on_prediction_ = false; // lo.slip_reference is prediction
  bool mean_imu_ = false;           // lo.imu_sampling is mean
  bool started_ = false;
  bool feet_placed_ = false;
  std::optional<int64_t> last_imu_ns_;
  Eigen::Vector3d last_accel_w_ = Eigen::Vector3d::Zero();  // held world acceleration (m/s^2, gravity removed)
  std::array<bool, kNumLegs> reported_stance_{{true, true, true, true}};
  std::array<Eigen::Vector3d, kNumLegs> roll_w_{};  // foot centre velocity from rolling, last reading (m/s)
  // Encoder readings of the last velocity window: the body's velocity through a foot is taken
  // over the window (a single finite difference of encoder positions is too noisy).
  struct WindowSample {
    int64_t t_ns = 0;
    Eigen::Vector3d p_w;                             // filter position after the reading (m)
    Eigen::Vector3d travel_w;                        // travel_w_ at the reading (m)
    std::array<Eigen::Vector3d, kNumLegs> rel_w;     // foot minus body, world axes (m)
    std::array<Eigen::Vector3d, kNumLegs> roll_w;    // rolling velocity of each foot centre (m/s)
  };
  std::deque<WindowSample> window_;
  // The body's travel by the filter's predictions alone (its velocity state integrated over the
  // IMU samples), without the jumps its measurement updates make in the position: the slip
  // gates' reference with lo.slip_reference: prediction.
  Eigen::Vector3d travel_w_ = Eigen::Vector3d::Zero();
  std::array<FootStatus, kNumLegs> feet_{};
  YawBiasFromFeet yaw_bias_;
  GravityTilt gravity_tilt_;
  int levellings_ = 0;
  // Set while the attitude's orientation was vision's at the last correction and the gyro alone
  // (with the gravity correction unless held) has turned it since: the time of that correction
  // (its last IMU sample's, ns); the next correction measures the bias.
  std::optional<int64_t> vision_reference_ns_;
  int vision_bias_updates_ = 0;
  // Rolling displacement of each foot's centre since its touch-down (m, world): the contact
  // point is the centre less it.
  std::array<Eigen::Vector3d, kNumLegs> rolled_w_{};
  // Where each stance foot's contact point was lo.slip_travel_from_s after touch-down, by the body's predicted
  // travel (travel_w_ + contact point relative to the body; m, world), for the slip by travel.
  std::array<std::optional<Eigen::Vector3d>, kNumLegs> settled_at_w_{};
  std::optional<int64_t> last_joints_ns_;
  double update_ms_sum_ = 0;
  long updates_ = 0;
};

}  // namespace viqu::lo

#include "slam/lo/leg_odometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/errors.h"

namespace viqu::lo {
namespace {

// Gravity in the world frame (m/s^2): a constant of the world, not a tuning parameter.
constexpr double kGravity = 9.81;

// Initial standard deviations of the filter: the start pose is the anchor (known), the robot is
// at rest, the feet are placed by the first kinematics. Small numbers, not tuning parameters.
constexpr double kStartPositionStd = 1e-3;  // (m)
constexpr double kStartVelocityStd = 0.05;  // (m/s)
constexpr double kStartFootStd = 0.01;      // (m)

}  // namespace

AttitudeFilterOptions AttitudeOptionsOf(const slam::LegOdometrySettings& s) {
  AttitudeFilterOptions o;
  o.attitude_gain = s.attitude_gain;
  o.gyro_bias_gain = s.gyro_bias_gain;
  o.gravity_gate_mps2 = s.gravity_gate_mps2;
  o.gravity_mps2 = kGravity;
  o.accel_average_s = s.attitude_accel_average_s;
  o.interval_mean = s.imu_sampling == "mean";
  return o;
}

YawBiasOptions YawBiasOptionsOf(const slam::LegOdometrySettings& s) {
  YawBiasOptions o;
  o.initial_std = s.yaw_bias_initial_std;
  o.walk = s.yaw_bias_walk;
  o.pair_noise_m = s.yaw_pair_noise_m;
  o.min_s = s.yaw_pair_min_s;
  o.max_s = s.yaw_pair_max_s;
  o.gate_chi2 = s.yaw_pair_gate_chi2;
  o.max_rate = s.yaw_pair_max_rate_radps;
  return o;
}

LegOdometry::LegOdometry(const slam::LegOdometrySettings& settings, const kin::LegKinematics& kin)
    : settings_(settings),
      kin_(kin),
      attitude_(AttitudeOptionsOf(settings)),
      yaw_bias_(YawBiasOptionsOf(settings)),
      gravity_tilt_(settings.fusion_tilt_window_s) {
  if (settings_.contact != "schedule" && settings_.contact != "touch" && settings_.contact != "estimated") {
    throw InputError("lo.contact must be schedule, touch or estimated, not '" + settings_.contact + "'");
  }
  estimated_contact_ = settings_.contact == "estimated";
  if (settings_.imu_sampling != "instant" && settings_.imu_sampling != "mean") {
    throw InputError("lo.imu_sampling must be instant or mean, not '" + settings_.imu_sampling + "'");
  }
  if (settings_.slip_reference != "position" && settings_.slip_reference != "prediction") {
    throw InputError("lo.slip_reference must be position or prediction, not '" + settings_.slip_reference + "'");
  }
  slip_on_prediction_ = settings_.slip_reference == "prediction";
  mean_imu_ = settings_.imu_sampling == "mean";
}

void LegOdometry::Start(int64_t t_ns, const Eigen::Isometry3d& T_w_body) {
  attitude_.Reset(t_ns, Eigen::Quaterniond(T_w_body.linear()));
  std::array<Eigen::Vector3d, kNumLegs> feet;
  feet.fill(T_w_body.translation());
  kf_.Reset(T_w_body.translation(), Eigen::Vector3d::Zero(), feet, kStartPositionStd, kStartVelocityStd, kStartFootStd);
  last_imu_ns_.reset();
  last_accel_w_.setZero();
  travel_w_.setZero();
  started_ = true;
  feet_placed_ = false;
  window_.clear();
  roll_w_.fill(Eigen::Vector3d::Zero());
  for (FootStatus& f : feet_) f = FootStatus{true, false, 0, t_ns, 0, false};
  settled_at_w_.fill(std::nullopt);
  yaw_bias_.Reset(t_ns);
  gravity_tilt_.Reset();
  levellings_ = 0;
  vision_reference_ns_.reset();
  vision_bias_updates_ = 0;
  rolled_w_.fill(Eigen::Vector3d::Zero());
  last_joints_ns_.reset();
}

Eigen::Isometry3d LegOdometry::T_w_body() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = attitude_.q_w_b().toRotationMatrix();
  T.translation() = kf_.position();
  return T;
}

std::optional<Eigen::Matrix3d> LegOdometry::Levelled(const Eigen::Matrix3d& R, double gate_deg) const {
  if (gate_deg <= 0) return std::nullopt;
  const std::optional<Eigen::Vector3d> level = gravity_tilt_.LevellingOf(R);
  if (!level || level->norm() <= gate_deg * M_PI / 180) return std::nullopt;
  return Eigen::AngleAxisd(level->norm(), level->normalized()).toRotationMatrix() * R;
}

void LegOdometry::SetOrientation(const Eigen::Matrix3d& R_w_b) {
  // The turn about the vertical, for the stance-pair headings measured so far.
  const Eigen::Matrix3d turn = R_w_b * attitude_.q_w_b().toRotationMatrix().transpose();
  yaw_bias_.TurnedBy(std::atan2(turn(1, 0), turn(0, 0)));
  attitude_.SetOrientation(Eigen::Quaterniond(R_w_b));
}

bool LegOdometry::CorrectPose(const Eigen::Isometry3d& T_w_body) {
  if (!started_) return false;
  kf_.Translate(T_w_body.translation() - kf_.position());
  const std::optional<Eigen::Matrix3d> levelled = Levelled(T_w_body.linear(), settings_.fusion_tilt_gate_deg);
  const int64_t t_ns = last_imu_ns_.value_or(0);
  if (settings_.fusion_gyro_bias_s > 0 && !levelled && vision_reference_ns_ && t_ns > *vision_reference_ns_) {
    // R_att = R0 Exp((w - b_est) dt) and R_vision = R0 Exp((w - b) dt), so R_att^T R_vision =
    // Exp((b_est - b) dt): the estimate's excess times the interval. Moving it by that rotation over
    // the time constant integrates (b_est - b) dt / tau; vision's error enters only as the
    // difference of its errors at the two ends, so it does not accumulate.
    const Eigen::AngleAxisd e(attitude_.q_w_b().toRotationMatrix().transpose() * T_w_body.linear());
    // A larger turn is not bias (the simulated bias, 3 sigma 0.006 rad/s, turns 0.3 mrad in a
    // 50 ms frame interval; vision's own error per frame is about 1 mrad): a relocalisation or a
    // jump of the map. Not a setting: it only guards against such jumps.
    constexpr double kMaxTurnRad = 0.01;
    if (std::abs(e.angle()) <= kMaxTurnRad) {
      attitude_.AddGyroBias(-(e.angle() / settings_.fusion_gyro_bias_s) * e.axis());
      ++vision_bias_updates_;
    }
  }
  SetOrientation(levelled ? *levelled : Eigen::Matrix3d(T_w_body.linear()));
  vision_reference_ns_ = levelled ? std::nullopt : std::optional<int64_t>(t_ns);
  // The window's body positions move with the correction, so that the next windowed velocity
  // does not see it as motion.
  window_.clear();
  if (levelled) ++levellings_;
  return levelled.has_value();
}

bool LegOdometry::KeepLevel() {
  if (!started_) return false;
  const std::optional<Eigen::Matrix3d> levelled =
      Levelled(attitude_.q_w_b().toRotationMatrix(), settings_.fusion_tilt_carry_gate_deg);
  if (!levelled) return false;
  vision_reference_ns_.reset();
  SetOrientation(*levelled);
  ++levellings_;
  return true;
}

void LegOdometry::AddImu(const ImuSample& s) {
  if (!started_) return;
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Quaterniond q_before = attitude_.q_w_b();
  attitude_.Add(s);
  // The raw rate: over the 2 s window a true bias of 0.002 rad/s turns the mean by 0.1 deg, while
  // the fused filter's own bias estimate winds up (vision resets its orientation every frame
  // against a gravity correction that leans with the gait: 0.027 rad/s after 250 s of
  // long_loop_corridor), which tilted the check by 1.8 deg there.
  gravity_tilt_.Add(s.t_ns, s.gyro_i, s.accel_i);
  const double dt = last_imu_ns_ ? (s.t_ns - *last_imu_ns_) * 1e-9 : 0.0;
  if (mean_imu_) {
    // The reading is the interval's mean specific force: it drives the interval, turned by the
    // mean of the orientations at its ends.
    last_accel_w_ = 0.5 * (q_before * s.accel_i + attitude_.q_w_b() * s.accel_i) - Eigen::Vector3d(0, 0, kGravity);
  }
  // instant: the previous reading's acceleration is held over the interval.
  // A stance foot that holds stays put but for its rolling; a swing or slipping foot is free.
  std::array<double, kNumLegs> foot_noise;
  std::array<Eigen::Vector3d, kNumLegs> foot_vel;
  for (int i = 0; i < kNumLegs; ++i) {
    const bool pinned = feet_[i].contact && !feet_[i].slipping;
    foot_noise[i] = pinned ? settings_.stance_foot_noise : settings_.swing_foot_noise;
    foot_vel[i] = pinned ? roll_w_[i] : Eigen::Vector3d::Zero();
  }
  const Eigen::Vector3d p_before = kf_.position();
  kf_.Predict(dt, last_accel_w_, settings_.accel_noise, foot_noise, foot_vel);
  travel_w_ += kf_.position() - p_before;
  last_imu_ns_ = s.t_ns;
  if (!mean_imu_) last_accel_w_ = attitude_.q_w_b() * s.accel_i - Eigen::Vector3d(0, 0, kGravity);
  update_ms_sum_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void LegOdometry::AddContact(const ContactReading& c) { reported_stance_ = c.stance; }

std::array<bool, kNumLegs> LegOdometry::ContactOf(const std::array<Eigen::Vector3d, kNumLegs>& rel_w) const {
  if (!estimated_contact_) return reported_stance_;
  // Estimated: the feet lowest along gravity are on the ground (flat-ground assumption; a slope
  // across the trunk's length tilts this, which is why it is not the default).
  double lowest = rel_w[0].z();
  for (const Eigen::Vector3d& r : rel_w) lowest = std::min(lowest, r.z());
  std::array<bool, kNumLegs> c{};
  for (int i = 0; i < kNumLegs; ++i) c[i] = rel_w[i].z() - lowest <= settings_.contact_height_m;
  return c;
}

void LegOdometry::AddJoints(const JointState& js) {
  if (!started_) return;
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Matrix3d R = attitude_.q_w_b().toRotationMatrix();
  const Eigen::Vector3d w_b = attitude_.angular_velocity();
  std::array<Eigen::Vector3d, kNumLegs> rel_w, vel_w;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg leg = static_cast<Leg>(i);
    const double q1 = js.position_rad[2 * i], q2 = js.position_rad[2 * i + 1];
    const Eigen::Vector3d r = kin_.FootInTrunk(leg, q1, q2);
    const Eigen::Vector2d qd(js.velocity_rad_s[2 * i], js.velocity_rad_s[2 * i + 1]);
    rel_w[i] = R * r;
    // A foot on the ground rolls: its centre moves at w_foot x (radius up), with the foot turning
    // at the trunk's rate plus the joint rates. The centre's velocity is also
    // v + R (w x r + J qd), so the body moves at that rolling velocity minus R (w x r + J qd).
    const Eigen::Vector3d w_foot_w = R * (w_b + kin_.ShankAngularVelocity(leg, qd.x(), qd.y()));
    roll_w_[i] = w_foot_w.cross(Eigen::Vector3d(0, 0, kin_.foot_radius()));
    vel_w[i] = roll_w_[i] - R * (w_b.cross(r) + kin_.FootJacobian(leg, q1, q2) * qd);
  }
  if (!feet_placed_) {
    // The first reading places the feet where the kinematics say, around the anchored body.
    std::array<Eigen::Vector3d, kNumLegs> feet;
    for (int i = 0; i < kNumLegs; ++i) feet[i] = kf_.position() + rel_w[i];
    kf_.Reset(kf_.position(), kf_.velocity(), feet, kStartPositionStd, kStartVelocityStd, kStartFootStd);
    feet_placed_ = true;
  }

  const std::array<bool, kNumLegs> contact = ContactOf(rel_w);
  const int64_t touchdown_ns = std::llround(settings_.touchdown_s * 1e9);
  const int64_t window_ns = std::llround(settings_.velocity_window_s * 1e9);
  const int64_t min_window_ns = std::llround(settings_.slip_min_window_s * 1e9);
  // Gate every stance foot against the prediction before any of them updates it.
  std::array<std::optional<Eigen::Vector3d>, kNumLegs> v_foot;  // body velocity through each foot, over its window
  std::array<double, kNumLegs> v_std{};                        // and its standard deviation (m/s)
  // Two gates. The chi-square one weighs the innovation by the filter's velocity variance, which
  // grows while feet are rejected, so a long slide is let back in; the speed gate holds a foot
  // out whatever that variance, but only while some stance foot agrees with the filter: when
  // none does, the filter has drifted, and gating every foot by it would leave it on the IMU.
  std::array<bool, kNumLegs> too_fast{};
  int agreeing = 0;  // stance feet within the speed limit of the filter
  for (int i = 0; i < kNumLegs; ++i) {
    FootStatus& f = feet_[i];
    if (contact[i] && !f.contact) f.touchdown_ns = js.t_ns;
    f.contact = contact[i];
    f.slipping = false;
    f.mahalanobis2 = 0;
    if (!f.contact) continue;
    // The window starts at the newest kept reading one window old, or, for a foot that touched
    // down more recently, at its touch-down: a shorter window, a noisier velocity.
    const WindowSample* ref = nullptr;
    for (const WindowSample& w : window_) {  // oldest first
      if (w.t_ns < f.touchdown_ns) continue;
      if (!ref || w.t_ns <= js.t_ns - window_ns) ref = &w;
    }
    if (!ref || js.t_ns - ref->t_ns < min_window_ns) continue;
    // Over the window the foot, if it held, moved only by rolling, so the body moved by the
    // foot's rolling minus the change of the foot-minus-body vector.
    const double dt = (js.t_ns - ref->t_ns) * 1e-9;
    v_foot[i] = 0.5 * (roll_w_[i] + ref->roll_w[i]) - (rel_w[i] - ref->rel_w[i]) / dt;
    v_std[i] = settings_.kin_velocity_noise_mps * std::max(1.0, settings_.velocity_window_s / dt);
    // The filter's own mean velocity over the same window.
    const Eigen::Vector3d v_mean =
        (slip_on_prediction_ ? travel_w_ - ref->travel_w : kf_.position() - ref->p_w) / dt;
    const Eigen::Vector3d innovation = *v_foot[i] - v_mean;
    f.mahalanobis2 = kf_.VelocityInnovationMahalanobis2(innovation, v_std[i]);
    f.slipping = f.mahalanobis2 > settings_.slip_gate_chi2;
    // The limit grows as the window shrinks, as the velocity's noise does.
    const double speed_limit = settings_.slip_speed_mps * std::max(1.0, settings_.velocity_window_s / dt);
    too_fast[i] = innovation.norm() > speed_limit;
    if (!too_fast[i]) ++agreeing;
  }
  if (agreeing > 0) {
    for (int i = 0; i < kNumLegs; ++i) feet_[i].slipping = feet_[i].slipping || too_fast[i];
  }
  for (int i = 0; i < kNumLegs; ++i) {
    const FootStatus& f = feet_[i];
    const bool settling = f.contact && js.t_ns - f.touchdown_ns < touchdown_ns;
    const Eigen::Vector3d inflate = settling ? Eigen::Vector3d(settings_.touchdown_inflation, settings_.touchdown_inflation,
                                                               settings_.touchdown_inflation_vertical)
                                             : Eigen::Vector3d::Ones();
    kf_.UpdateFootPosition(i, rel_w[i], settings_.kin_position_noise_m * inflate);
    if (f.contact && !f.slipping && v_foot[i]) kf_.UpdateVelocity(*v_foot[i], v_std[i] * inflate);
  }
  // The gyro bias about the vertical from pairs of feet that hold (settled, not slipping).
  const double reading_dt = last_joints_ns_ ? (js.t_ns - *last_joints_ns_) * 1e-9 : 0.0;
  last_joints_ns_ = js.t_ns;
  std::array<bool, kNumLegs> holds{};
  std::array<Eigen::Vector3d, kNumLegs> contact_w;
  for (int i = 0; i < kNumLegs; ++i) {
    const FootStatus& f = feet_[i];
    if (!f.contact || f.touchdown_ns == js.t_ns) rolled_w_[i].setZero();
    else rolled_w_[i] += roll_w_[i] * reading_dt;
    holds[i] = f.contact && !f.slipping && js.t_ns - f.touchdown_ns >= touchdown_ns;
    contact_w[i] = rel_w[i] - rolled_w_[i];
  }
  // The slip by travel: each stance foot's contact point against the body's predicted travel
  // since lo.slip_travel_from_s after its touch-down (the filter's velocity integrated: it follows
  // the feet the gates let in).
  const int64_t travel_from_ns = std::llround(settings_.slip_travel_from_s * 1e9);
  for (int i = 0; i < kNumLegs; ++i) {
    FootStatus& f = feet_[i];
    if (!f.contact || js.t_ns - f.touchdown_ns < travel_from_ns) {
      settled_at_w_[i].reset();
      f.travel_m = 0;
      if (!f.contact) f.slipped = false;
      continue;
    }
    // The contact point by the body's predicted travel (any origin: only its changes count).
    const Eigen::Vector3d at_w = travel_w_ + contact_w[i];
    if (!settled_at_w_[i]) {
      settled_at_w_[i] = at_w;
      f.slipped = false;
    }
    f.travel_m = (at_w - *settled_at_w_[i]).head<2>().norm();
    f.slipped = f.slipped || f.travel_m > settings_.slip_travel_m;
  }
  const double yaw_rate = (R * w_b).z();
  if (const std::optional<double> db = yaw_bias_.Add(js.t_ns, holds, contact_w, yaw_rate)) {
    attitude_.AddGyroBias(R.transpose() * Eigen::Vector3d(0, 0, *db));
  }
  // Keep the readings of the last window (and the one just before it).
  window_.push_back(WindowSample{js.t_ns, kf_.position(), travel_w_, rel_w, roll_w_});
  while (window_.size() > 2 && window_[1].t_ns <= js.t_ns - window_ns) window_.pop_front();
  update_ms_sum_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ++updates_;
}

}  // namespace viqu::lo

#include "slam/fusion/gyro_motion_prior.h"

#include <cmath>

namespace viqu::slam {

GyroMotionPrior::GyroMotionPrior(const lo::AttitudeFilterOptions& options, const Eigen::Isometry3d& T_imu_cam)
    : options_(options), attitude_(options), T_imu_cam_(T_imu_cam) {}

void GyroMotionPrior::AddImu(const ImuSample& s) {
  if (!attitude_.started()) {
    // Started levelled (the measured specific force turned to +z) by the first sample that reads
    // about g: a recording may begin in free fall or with a jolt (viqu's first sample reads 0),
    // and a start tilted by that would be pulled back by the gravity correction only over
    // seconds, turning every frame's prior meanwhile.
    if (std::abs(s.accel_i.norm() - options_.gravity_mps2) > options_.gravity_gate_mps2) return;
    attitude_.Reset(s.t_ns, Eigen::Quaterniond::FromTwoVectors(s.accel_i, Eigen::Vector3d::UnitZ()));
  }
  attitude_.Add(s);
}

std::optional<Eigen::Isometry3d> GyroMotionPrior::Prior(int64_t t_ns) const {
  if (!T_w_imu_last_ || !oriented_at_frame_) return std::nullopt;
  // The IMU's rotation from the last frame to this one, in the IMU frame of the last frame.
  const Eigen::Matrix3d dR = (q_at_frame_.conjugate() * attitude_.OrientationAt(t_ns)).toRotationMatrix();
  Eigen::Isometry3d T_w_imu = Eigen::Isometry3d::Identity();
  T_w_imu.linear() = T_w_imu_last_->linear() * dR;
  Eigen::Vector3d step = Eigen::Vector3d::Zero();
  if (T_w_imu_before_ && frame_ns_ > before_ns_) {
    step = (T_w_imu_last_->translation() - T_w_imu_before_->translation()) *
           (static_cast<double>(t_ns - frame_ns_) / static_cast<double>(frame_ns_ - before_ns_));
  }
  T_w_imu.translation() = T_w_imu_last_->translation() + step;
  const Eigen::Isometry3d T_w_cam_last = *T_w_imu_last_ * T_imu_cam_;
  const Eigen::Isometry3d T_w_cam = T_w_imu * T_imu_cam_;
  return T_w_cam.inverse() * T_w_cam_last;
}

std::optional<Eigen::Isometry3d> GyroMotionPrior::NextFrame(int64_t t_ns) {
  const std::optional<Eigen::Isometry3d> prior = Prior(t_ns);
  if (prior) ++priors_given_;
  q_at_frame_ = attitude_.OrientationAt(t_ns);
  oriented_at_frame_ = attitude_.started();
  return prior;
}

void GyroMotionPrior::BeforeTrack(SlamSystem* system, int64_t t_ns) {
  if (const std::optional<Eigen::Isometry3d> prior = NextFrame(t_ns)) system->SetMotionPrior(*prior);
}

void GyroMotionPrior::AfterTrack(const TrackResult& r) {
  // A frame with a pose from vision (tracked, relocalised, or the start of a map segment).
  if (r.status == TrackStatus::kLost) {
    T_w_imu_last_.reset();
    T_w_imu_before_.reset();
  } else {
    T_w_imu_before_ = T_w_imu_last_;  // empty unless the last frame had one too
    before_ns_ = frame_ns_;
    T_w_imu_last_ = r.T_w_c * T_imu_cam_.inverse();
  }
  frame_ns_ = r.t_ns;
}

}  // namespace viqu::slam

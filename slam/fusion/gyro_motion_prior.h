#pragma once
// A motion prior from a gyroscope alone (slam.mode full on a dataset with an IMU but no leg
// encoders, e.g. EuRoC's imu0). Per camera frame:
//  - rotation: the attitude filter's (gyro integration, gravity correction of roll and pitch,
//    gyro bias on the axes gravity observes) change of the IMU's orientation from the last frame
//    to this one, extrapolated from the last sample to the frame's stamp with the last rate;
//  - translation: the IMU (body) keeps the velocity of its last two tracked frames, and the
//    camera follows it with its lever arm (so that a rotation about the IMU moves the camera).
// This replaces the tracker's constant-velocity guess, whose rotation part is what misses on a
// jolt. No prior before the first frame with a pose from vision and an orientation from the
// filter, nor after a lost frame (the tracker's own logic then decides).
#include <cstdint>
#include <optional>

#include <Eigen/Geometry>

#include "slam/core/slam_system.h"
#include "slam/lo/attitude_filter.h"
#include "slam/measurements/imu_sample.h"

namespace viqu::slam {

class GyroMotionPrior {
 public:
  // T_imu_cam: the frames' (left, rectified) camera in the IMU frame.
  GyroMotionPrior(const lo::AttitudeFilterOptions& options, const Eigen::Isometry3d& T_imu_cam);

  // IMU samples in time order (AttitudeFilter::Add throws otherwise). The first one that reads about
  // g (within gravity_gate_mps2) starts the attitude filter levelled by it; earlier ones are
  // ignored. The world's yaw is arbitrary: only changes of orientation are used.
  void AddImu(const ImuSample& s);

  // The camera motion from the last frame to a frame at t_ns (T_cur_last), or nullopt (see above).
  std::optional<Eigen::Isometry3d> Prior(int64_t t_ns) const;
  // A new frame at t_ns: returns Prior(t_ns) and remembers the orientation at t_ns.
  std::optional<Eigen::Isometry3d> NextFrame(int64_t t_ns);
  // NextFrame(t_ns), handed to `system` when there is a prior.
  void BeforeTrack(SlamSystem* system, int64_t t_ns);
  // Takes the frame's tracked pose as the base of the next prior.
  void AfterTrack(const TrackResult& r);

  int priors_given() const { return priors_given_; }

 private:
  lo::AttitudeFilterOptions options_;
  lo::AttitudeFilter attitude_;  // started (Reset) by the first sample that reads about g
  Eigen::Isometry3d T_imu_cam_;
  // At the last frame: the filter's orientation and the frame's time; the IMU poses from vision
  // of the last two frames (the older one only when both had one).
  Eigen::Quaterniond q_at_frame_ = Eigen::Quaterniond::Identity();
  bool oriented_at_frame_ = false;  // the filter had started at the last frame
  int64_t frame_ns_ = 0;
  std::optional<Eigen::Isometry3d> T_w_imu_last_, T_w_imu_before_;
  int64_t before_ns_ = 0;
  int priors_given_ = 0;
};

}  // namespace viqu::slam

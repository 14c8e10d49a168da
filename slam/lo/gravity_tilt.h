#pragma once
// Which way is up over the last few seconds, from the IMU alone: the specific force averaged over
// a window, each sample turned into the current body frame by the gyro's rotation since (the
// gyro alone, so that a correction of the attitude from elsewhere does not enter). While walking
// the body's mean acceleration over seconds is small (a speed change of 0.12 m/s over 2 s is
// 0.06 m/s^2, 0.35 deg), so the mean force points up to about half a degree: on static_room's
// trot, with a 2 s window, the true orientation's tilt from it has a median of 0.43 deg and a
// maximum of 1.9 deg (session 36). Unlike each sample's normalised direction (the attitude
// filter's gravity correction), the mean of the raw force does not lean with the gait's
// correlated accelerations. The fusion uses it to catch a visual orientation that has tilted
// (a tracker on few points before a loss): a check, not an estimator of its own.
#include <cstdint>
#include <deque>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace viqu::lo {

class GravityTilt {
 public:
  // window_s: the averaging window (s); the check answers once a whole window has been seen.
  explicit GravityTilt(double window_s) : window_ns_(static_cast<int64_t>(window_s * 1e9)) {}

  // Forgets every sample.
  void Reset();
  // One IMU sample at t_ns: the gyro rate (rad/s, body; its bias taken out if known) and the
  // specific force (m/s^2, body). The rotation since the previous sample is the mean of the two
  // rates.
  void Add(int64_t t_ns, const Eigen::Vector3d& gyro_b, const Eigen::Vector3d& accel_b);

  // The rotation (world frame, axis times angle in rad, horizontal) that turns the orientation
  // R_w_b so that the window's mean force points straight up; none before a whole window.
  std::optional<Eigen::Vector3d> LevellingOf(const Eigen::Matrix3d& R_w_b) const;

  // The window's mean specific force in the current body frame (m/s^2); none before a whole window.
  std::optional<Eigen::Vector3d> MeanForceBody() const;

 private:
  struct Entry {
    int64_t t_ns;
    Eigen::Vector3d sum;  // running sum of the forces in the gyro frame, this sample included
    long count;           // samples in that sum
  };
  int64_t window_ns_;
  Eigen::Quaterniond q_g_b_ = Eigen::Quaterniond::Identity();  // body in the gyro frame
  Eigen::Vector3d last_gyro_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  long count_ = 0;
  std::optional<int64_t> last_t_ns_;
  std::deque<Entry> entries_;  // oldest first; the front is at most one window old but the first
};

}  // namespace viqu::lo

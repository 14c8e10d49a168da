#pragma once
// The proprioceptive streams of a viqu recording (`viqu run --record`): imu0, joints0, contact0
// and robot.urdf beside the images, for leg odometry in a replay (`viqu slam --format viqu` in
// slam.mode full). Values were written with the digits they need to read back exactly: the
// replay reads the very doubles of the live run.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "slam/measurements/contact_reading.h"
#include "slam/measurements/ground_truth_pose.h"
#include "slam/measurements/imu_sample.h"
#include "slam/measurements/joint_state.h"

namespace viqu::io {

struct Proprioception {
  std::vector<ImuSample> imu;
  std::vector<JointState> joints;      // contact: the simulator's truth (metrics only, never the estimator)
  std::vector<ContactReading> touch;   // foot touch sensors
  std::vector<ContactReading> planned; // the gait controller's planned stance
  std::string urdf_path;               // mav0/robot.urdf
  Eigen::Isometry3d T_body_cam0 = Eigen::Isometry3d::Identity();  // left camera in the trunk
  std::optional<StampedPose> body_at_start;  // ground truth of the trunk at its first row
};

// Reads DIR/dataset/mav0 or DIR/mav0. nullopt when the recording has no joints0 or contact0 or
// robot.urdf (older recordings, other datasets); InputError naming FILE:LINE for a malformed
// row, a non-finite value or stamps that do not increase.
std::optional<Proprioception> ReadViquProprioception(const std::string& dir);

}  // namespace viqu::io

#pragma once
// The simulated world of one scenario: the composed MuJoCo model and its state, the scripted
// obstacles, and ground-truth queries about the robot. Owns mjModel and mjData.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "scenario/scenario.h"
#include "sim/mujoco_handles.h"
#include "sim/obstacles.h"
#include "slam/measurements/ground_truth_pose.h"
#include "slam/measurements/joint_state.h"

namespace viqu::sim {

class World {
 public:
  // Composes and loads the scene (world + robot + obstacles + terrain), sets the floor friction,
  // the camera fovy and baseline, and places the robot at its start pose standing on
  // `q_stand` (joint angles, rad) with its trunk `stand_height_m` above the floor.
  World(const Scenario& s, const std::array<double, kNumJoints>& q_stand, double stand_height_m);

  const mjModel* model() const { return model_.get(); }
  mjData* data() { return data_.get(); }
  const mjData* data() const { return data_.get(); }

  // Position-servo targets of the eight joints (rad).
  void SetJointTargets(const std::array<double, kNumJoints>& q);

  // One physics step: obstacles move to the current time, the scenario's pushes act on the
  // trunk (xfrc_applied), then mj_step.
  void Step();

  int64_t time_ns() const;  // simulated time (ns)
  int64_t timestep_ns() const { return timestep_ns_; }

  GroundTruthState GroundTruth() const;
  std::array<double, kNumJoints> JointPositions() const;   // (rad)
  std::array<double, kNumJoints> JointVelocities() const;  // (rad/s)
  std::array<bool, kNumLegs> FootContacts() const;          // foot touches a non-robot geom
  std::array<double, kNumLegs> FootNormalForces() const;    // contact normal force on each foot (N)
  Eigen::Vector3d FootPositionWorld(Leg leg) const;         // foot centre (m)
  Eigen::Vector3d FootVelocityWorld(Leg leg) const;         // foot centre velocity (m/s)
  // Velocity of the foot's material point at its lowest point (where it touches flat ground):
  // the centre velocity plus the foot's rotation about it. This is the slip velocity of a foot
  // in contact; the centre alone also moves when the foot rolls (m/s).
  Eigen::Vector3d FootSoleVelocityWorld(Leg leg) const;
  Eigen::Vector3d TrueAccel() const;  // accelerometer reading without noise (m/s^2, IMU frame)
  Eigen::Vector3d TrueGyro() const;   // gyro reading without noise (rad/s, IMU frame)
  // The means of the accelerometer and gyro readings of the physics steps since the last call
  // (each step's readings are those of the state it started from), and starts a new interval;
  // before any step, the current readings.
  struct ImuMean {
    Eigen::Vector3d accel_i, gyro_i;
  };
  ImuMean TakeImuMean();
  // The torque each leg servo applies to its joint (N m, joint order of JointPositions), as a
  // motor-current reading would give it: MuJoCo's actuator force on the joint (qfrc_actuator).
  // mj_step computes it from the state the step starts from, so after a step it is the torque
  // applied over that step, [t - dt, t): one physics step behind JointPositions(). Before any
  // step, that of the initial state.
  std::array<double, kNumJoints> JointTorques() const;
  // The mean of JointTorques() over the physics steps since the last call, and starts a new
  // interval; before any step, JointTorques().
  std::array<double, kNumJoints> TakeJointTorqueMean();
  bool TrunkTouchesGround() const;    // trunk or head geom in contact with a non-robot geom
  double TrunkTiltRad() const;        // angle between trunk z and world z (rad)

  // Left and right optical camera frames in the trunk frame (fixed).
  Eigen::Isometry3d T_body_cam(bool right) const;

  const ObstacleSet& obstacles() const { return *obstacles_; }
  const std::string& composed_xml() const { return xml_; }

 private:
  bool IsRobotGeom(int geom) const;
  // The leg whose foot touches a non-robot geom in contact `contact` of mjData, or -1.
  int FootOfContact(int contact) const;

  std::string xml_;
  ModelPtr model_;
  DataPtr data_;
  std::unique_ptr<ObstacleSet> obstacles_;
  int64_t timestep_ns_ = 0;
  int trunk_body_ = -1;
  int cam_left_ = -1, cam_right_ = -1;
  int accel_adr_ = -1, gyro_adr_ = -1;  // sensordata addresses
  Eigen::Vector3d accel_sum_ = Eigen::Vector3d::Zero(), gyro_sum_ = Eigen::Vector3d::Zero();
  int imu_steps_ = 0;                     // physics steps summed in accel_sum_ / gyro_sum_
  std::array<double, kNumJoints> torque_sum_{};  // JointTorques() summed over torque_steps_ steps (N m)
  int torque_steps_ = 0;
  std::array<int, kNumJoints> qpos_adr_{}, dof_adr_{}, actuator_{};
  std::array<int, kNumLegs> foot_geom_{}, foot_site_{};
  std::vector<int> trunk_geoms_;
  std::vector<Disturbance> disturbances_;
};

}  // namespace viqu::sim

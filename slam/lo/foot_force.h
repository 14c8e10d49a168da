#pragma once
// The ground's force on each foot from the servos' torque readings (issue 55, item 2), through
// the transposed Jacobian of the one URDF kinematics (kinematics/). slam/ sees no MuJoCo: the
// simulator's contact forces are truth for tests and metrics only.
//
// Per leg, the balance of the two pitch joints, with the servo's rotor inertia (armature) kept
// and the links' own inertia and the velocity-product terms neglected (a 20 g thigh 25 mm from
// its axis has 1.25e-5 kg m^2 against the armature's 2e-4):
//   a qdd = tau_servo + tau_gravity(q, g) - b qd + J(q)^T F
// so the ground's force on the foot F (trunk frame) solves
//   J^T F = a qdd + b qd - tau_servo - tau_gravity,
// in the leg's sagittal plane (the trunk's x-z: the legs only pitch, so a sideways force is not
// seen and comes out 0). qdd is the backward difference of the encoder's velocities.
#include <array>

#include <Eigen/Core>

#include "kinematics/leg_kinematics.h"
#include "slam/measurements/joint_state.h"

namespace viqu::lo {

// The estimator's model of the servos: the damping and armature of models/rat/rat.xml's joints.
// A description of the robot, not a tuning: it becomes an lo setting when the filter uses the
// forces (issue 55, item 3).
struct FootForceModel {
  double damping_nms = 0.03;       // joint damping b (N m s / rad)
  double armature_kgm2 = 0.0002;   // rotor inertia a reflected at the joint (kg m^2)
  // A leg whose 2x2 sagittal Jacobian has |det| below this (m^2) is too near straight for its
  // torques to tell a force (its knee within about 5 deg of full extension on this robot):
  // no estimate. Geometry, not a tuning.
  double min_jacobian_det_m2 = 2e-4;
};

// How the estimate lines up the readings. The encoder's velocity is the difference of its last
// two positions (sim/encoder_model.h), so it belongs half a sample back, and the difference of two
// velocities (qdd) a whole sample back. `current` takes the newest torque, angle and velocity with
// that qdd, at the newest reading's time (as first written); `centred` takes the previous
// reading's torque and angle, the mean of the last two velocities and that qdd, all about the
// previous reading's time, and dates the estimate there (one encoder period late).
enum class ForceAlignment { kCurrent, kCentred };

struct FootForces {
  int64_t t_ns = 0;
  std::array<Eigen::Vector3d, kNumLegs> f_trunk{};  // the ground's force on each foot, trunk frame (N)
  std::array<bool, kNumLegs> valid{};               // false: no reading, or the leg near straight
};

class FootForceEstimator {
 public:
  FootForceEstimator(const kin::LegKinematics& kin, const FootForceModel& model = {},
                     ForceAlignment alignment = ForceAlignment::kCurrent);

  // One encoder + torque reading; `g_trunk` is gravity in the trunk frame (m/s^2, e.g.
  // R_world_trunk^T (0, 0, -9.81) from the attitude filter). A reading without torque gives no
  // estimate (every leg invalid), as does the first one when centred. The estimate's t_ns says
  // which instant it belongs to.
  FootForces Update(const JointState& js, const Eigen::Vector3d& g_trunk);

 private:
  const kin::LegKinematics& kin_;
  FootForceModel model_;
  ForceAlignment alignment_;
  bool have_last_ = false;
  JointState last_;  // the previous reading
};

}  // namespace viqu::lo

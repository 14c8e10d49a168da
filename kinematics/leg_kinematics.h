#pragma once
// Forward and inverse kinematics of the rat's legs, read from the URDF (the kinematic truth).
// One implementation serves the gait controller (inverse) and the leg odometry (forward).
#include <array>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "slam/measurements/joint_state.h"

namespace viqu::kin {

// One leg's chain, every transform in the parent's frame, read from the URDF.
struct LegChain {
  Eigen::Isometry3d T_trunk_hip = Eigen::Isometry3d::Identity();    // hip joint origin in trunk
  Eigen::Vector3d hip_axis = -Eigen::Vector3d::UnitY();              // unit axis, hip joint frame
  Eigen::Isometry3d T_thigh_knee = Eigen::Isometry3d::Identity();   // knee joint origin in thigh
  Eigen::Vector3d knee_axis = -Eigen::Vector3d::UnitY();             // unit axis, knee joint frame
  Eigen::Isometry3d T_shank_foot = Eigen::Isometry3d::Identity();   // foot centre in shank
  double hip_lower = 0, hip_upper = 0;    // joint limits (rad)
  double knee_lower = 0, knee_upper = 0;  // joint limits (rad)
  // The moving links' masses and centres of mass, from the URDF's <inertial> (a link without one
  // weighs nothing): the thigh in its own frame, the shank with the foot link in the shank's.
  double thigh_mass_kg = 0, shank_mass_kg = 0;
  Eigen::Vector3d thigh_com = Eigen::Vector3d::Zero();  // (m, thigh frame)
  Eigen::Vector3d shank_com = Eigen::Vector3d::Zero();  // (m, shank frame)
};

class LegKinematics {
 public:
  // Reads the URDF; throws viqu::InputError naming the file when it cannot be parsed, a leg
  // joint is missing (FL_hip, FL_knee, FL_foot_fixed, ...), or the legs are not the planar
  // two-link legs of paper eq. 6 (parallel pitch axes, links along -z at zero angles).
  static LegKinematics FromUrdfFile(const std::string& path);
  static LegKinematics FromUrdfString(const std::string& xml, const std::string& what);

  // Foot centre in the trunk frame for joint angles (theta1 hip, theta2 knee) (m, rad).
  Eigen::Vector3d FootInTrunk(Leg leg, double theta1, double theta2) const;

  // d(FootInTrunk)/d(theta1, theta2), 3x2.
  Eigen::Matrix<double, 3, 2> FootJacobian(Leg leg, double theta1, double theta2) const;

  // The torques gravity applies at the leg's joints through its own links (N m, theta1 then
  // theta2; positive along the joint axes), for the gravity vector in the trunk frame
  // (g_trunk = R_trunk_world * (0, 0, -9.81)): sum over links of J_com^T m g.
  Eigen::Vector2d GravityTorque(Leg leg, double theta1, double theta2, const Eigen::Vector3d& g_trunk) const;

  // Joint angles that put the foot centre at p_trunk_foot (its component along the pitch axis is
  // ignored: a sagittal leg cannot move its foot sideways). Picks the knee-backward solution
  // (theta2 > 0). Returns false, with the nearest reachable angles, if the point is out of reach
  // or outside the joint limits.
  bool Inverse(Leg leg, const Eigen::Vector3d& p_trunk_foot, double* theta1, double* theta2) const;

  const LegChain& chain(Leg leg) const { return legs_[static_cast<int>(leg)]; }
  double thigh_length() const { return l1_; }  // l1 (m)
  double shank_length() const { return l2_; }  // l2 (m)
  double total_mass() const { return total_mass_; }  // sum of all URDF link masses (kg)
  // Radius of the foot sphere (m), from the foot links' <collision><sphere>: the foot centre sits
  // this high above the ground, and rolls over it as the shank turns.
  double foot_radius() const { return foot_radius_; }

  // Angular velocity of the shank (and the foot) relative to the trunk, in the trunk frame, for
  // joint rates (rad/s): both pitch axes are parallel (checked on loading).
  Eigen::Vector3d ShankAngularVelocity(Leg leg, double theta1_dot, double theta2_dot) const;

 private:
  std::array<LegChain, kNumLegs> legs_;
  double l1_ = 0, l2_ = 0;
  double total_mass_ = 0;
  double foot_radius_ = 0;
};

}  // namespace viqu::kin

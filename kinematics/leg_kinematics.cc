#include "kinematics/leg_kinematics.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "common/errors.h"
#include "common/input_file.h"

namespace viqu::kin {
namespace {

constexpr double kGeomTol = 1e-9;  // tolerance for "is along the axis" checks (m or unitless)

// Collects urdfdom's errors and warnings (console_bridge) instead of printing them.
class UrdfMessages : public console_bridge::OutputHandler {
 public:
  void log(const std::string& message, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_WARN) return;
    if (!text.empty()) text += "; ";
    text += message;
  }
  std::string text;
};

Eigen::Isometry3d ToIsometry(const urdf::Pose& p) {
  double qx, qy, qz, qw;
  p.rotation.getQuaternion(qx, qy, qz, qw);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return T;
}

Eigen::Isometry3d RotationAbout(const Eigen::Vector3d& axis, double angle) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  return T;
}

urdf::JointConstSharedPtr JointOrThrow(const urdf::ModelInterface& model, const std::string& name,
                                       const std::string& what) {
  auto j = model.getJoint(name);
  if (!j) throw InputError(what + ": URDF has no joint '" + name + "'");
  return j;
}

// A sagittal two-link leg: knee and foot offsets straight down, axes along +-y, no hip rotation.
void CheckPlanarLeg(const LegChain& c, const std::string& leg, const std::string& what) {
  const auto bad = [&](const std::string& why) {
    throw InputError(what + ": leg " + leg + " is not a planar two-link leg (paper eq. 6): " + why);
  };
  if (!c.T_trunk_hip.linear().isIdentity(kGeomTol)) bad("hip joint origin is rotated");
  if (std::abs(std::abs(c.hip_axis.y()) - 1) > kGeomTol) bad("hip axis is not along y");
  if (!c.knee_axis.isApprox(c.hip_axis, kGeomTol)) bad("knee axis differs from hip axis");
  if (!c.T_thigh_knee.linear().isIdentity(kGeomTol) || !c.T_shank_foot.linear().isIdentity(kGeomTol))
    bad("knee or foot origin is rotated");
  const Eigen::Vector3d k = c.T_thigh_knee.translation(), f = c.T_shank_foot.translation();
  if (std::abs(k.x()) > kGeomTol || std::abs(k.y()) > kGeomTol || k.z() >= 0) bad("knee not below hip");
  if (std::abs(f.x()) > kGeomTol || std::abs(f.y()) > kGeomTol || f.z() >= 0) bad("foot not below knee");
}

}  // namespace

LegKinematics LegKinematics::FromUrdfFile(const std::string& path) {
  // A URDF of a robot is a few KiB to a few hundred (meshes are other files).
  constexpr uintmax_t kMaxUrdfFileBytes = uintmax_t{16} << 20;
  return FromUrdfString(ReadInputFile(path, kMaxUrdfFileBytes, "URDF file"), path);
}

LegKinematics LegKinematics::FromUrdfString(const std::string& xml, const std::string& what) {
  // urdfdom reports parse errors through console_bridge, to stderr by default: catch them, so
  // that the first line a user sees is ours, naming the file, with urdfdom's reason after it.
  UrdfMessages messages;
  console_bridge::useOutputHandler(&messages);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (...) {
    console_bridge::restorePreviousOutputHandler();
    throw;
  }
  console_bridge::restorePreviousOutputHandler();
  if (!model) throw InputError(what + ": cannot parse URDF" + (messages.text.empty() ? "" : " (" + messages.text + ")"));
  LegKinematics k;
  for (int i = 0; i < kNumLegs; ++i) {
    const std::string leg = LegName(static_cast<Leg>(i));
    const auto hip = JointOrThrow(*model, leg + "_hip", what);
    const auto knee = JointOrThrow(*model, leg + "_knee", what);
    const auto foot = JointOrThrow(*model, leg + "_foot_fixed", what);
    if (hip->parent_link_name != "trunk" || knee->parent_link_name != hip->child_link_name ||
        foot->parent_link_name != knee->child_link_name) {
      throw InputError(what + ": leg " + leg + " is not the chain trunk -> hip -> knee -> foot");
    }
    LegChain& c = k.legs_[i];
    c.T_trunk_hip = ToIsometry(hip->parent_to_joint_origin_transform);
    c.hip_axis = Eigen::Vector3d(hip->axis.x, hip->axis.y, hip->axis.z).normalized();
    c.T_thigh_knee = ToIsometry(knee->parent_to_joint_origin_transform);
    c.knee_axis = Eigen::Vector3d(knee->axis.x, knee->axis.y, knee->axis.z).normalized();
    c.T_shank_foot = ToIsometry(foot->parent_to_joint_origin_transform);
    if (!hip->limits || !knee->limits) throw InputError(what + ": leg " + leg + " joints need <limit>");
    c.hip_lower = hip->limits->lower;
    c.hip_upper = hip->limits->upper;
    c.knee_lower = knee->limits->lower;
    c.knee_upper = knee->limits->upper;
    CheckPlanarLeg(c, leg, what);
    const auto mass_of = [&](const std::string& link_name, Eigen::Vector3d* com) {
      const auto link = model->getLink(link_name);
      if (!link || !link->inertial) return 0.0;
      const urdf::Vector3& o = link->inertial->origin.position;
      *com = Eigen::Vector3d(o.x, o.y, o.z);
      return link->inertial->mass;
    };
    c.thigh_mass_kg = mass_of(hip->child_link_name, &c.thigh_com);
    c.shank_mass_kg = mass_of(knee->child_link_name, &c.shank_com);
    Eigen::Vector3d foot_com = Eigen::Vector3d::Zero();
    const double foot_mass = mass_of(foot->child_link_name, &foot_com);
    if (foot_mass > 0) {  // folded into the shank: one rigid body
      const Eigen::Vector3d p = c.T_shank_foot * foot_com;
      c.shank_com = (c.shank_mass_kg * c.shank_com + foot_mass * p) / (c.shank_mass_kg + foot_mass);
      c.shank_mass_kg += foot_mass;
    }
    const double l1 = -c.T_thigh_knee.translation().z(), l2 = -c.T_shank_foot.translation().z();
    const auto foot_link = model->getLink(foot->child_link_name);
    const auto* sphere = foot_link && foot_link->collision && foot_link->collision->geometry
                             ? dynamic_cast<const urdf::Sphere*>(foot_link->collision->geometry.get())
                             : nullptr;
    if (!sphere || !(sphere->radius > 0)) {
      throw InputError(what + ": link " + foot->child_link_name + " needs <collision><geometry><sphere radius=...>");
    }
    if (i == 0) {
      k.foot_radius_ = sphere->radius;
    } else if (std::abs(sphere->radius - k.foot_radius_) > kGeomTol) {
      throw InputError(what + ": leg " + leg + " has a different foot radius than FL");
    }
    if (i == 0) {
      k.l1_ = l1;
      k.l2_ = l2;
    } else if (std::abs(l1 - k.l1_) > kGeomTol || std::abs(l2 - k.l2_) > kGeomTol) {
      throw InputError(what + ": leg " + leg + " has different link lengths than FL");
    }
  }
  for (const auto& [name, link] : model->links_) {
    if (link->inertial) k.total_mass_ += link->inertial->mass;
  }
  return k;
}

Eigen::Vector3d LegKinematics::FootInTrunk(Leg leg, double theta1, double theta2) const {
  const LegChain& c = chain(leg);
  const Eigen::Isometry3d T = c.T_trunk_hip * RotationAbout(c.hip_axis, theta1) * c.T_thigh_knee *
                              RotationAbout(c.knee_axis, theta2) * c.T_shank_foot;
  return T.translation();
}

Eigen::Matrix<double, 3, 2> LegKinematics::FootJacobian(Leg leg, double theta1, double theta2) const {
  const LegChain& c = chain(leg);
  const Eigen::Isometry3d T_trunk_thigh = c.T_trunk_hip * RotationAbout(c.hip_axis, theta1);
  const Eigen::Isometry3d T_trunk_shank = T_trunk_thigh * c.T_thigh_knee * RotationAbout(c.knee_axis, theta2);
  const Eigen::Vector3d p_foot = (T_trunk_shank * c.T_shank_foot).translation();
  Eigen::Matrix<double, 3, 2> J;
  const Eigen::Vector3d a1 = T_trunk_thigh.linear() * c.hip_axis;
  const Eigen::Vector3d a2 = T_trunk_shank.linear() * c.knee_axis;
  J.col(0) = a1.cross(p_foot - T_trunk_thigh.translation());
  J.col(1) = a2.cross(p_foot - T_trunk_shank.translation());
  return J;
}

Eigen::Vector2d LegKinematics::GravityTorque(Leg leg, double theta1, double theta2, const Eigen::Vector3d& g_trunk) const {
  const LegChain& c = chain(leg);
  const Eigen::Isometry3d T_trunk_thigh = c.T_trunk_hip * RotationAbout(c.hip_axis, theta1);
  const Eigen::Isometry3d T_trunk_shank = T_trunk_thigh * c.T_thigh_knee * RotationAbout(c.knee_axis, theta2);
  const Eigen::Vector3d a1 = T_trunk_thigh.linear() * c.hip_axis;
  const Eigen::Vector3d a2 = T_trunk_shank.linear() * c.knee_axis;
  const Eigen::Vector3d o1 = T_trunk_thigh.translation(), o2 = T_trunk_shank.translation();
  const Eigen::Vector3d p_thigh = T_trunk_thigh * c.thigh_com, p_shank = T_trunk_shank * c.shank_com;
  const Eigen::Vector3d f_thigh = c.thigh_mass_kg * g_trunk, f_shank = c.shank_mass_kg * g_trunk;
  // The torque of a force f at p about a joint's axis a through o: a . ((p - o) x f).
  Eigen::Vector2d tau;
  tau[0] = a1.dot((p_thigh - o1).cross(f_thigh)) + a1.dot((p_shank - o1).cross(f_shank));
  tau[1] = a2.dot((p_shank - o2).cross(f_shank));
  return tau;
}

Eigen::Vector3d LegKinematics::ShankAngularVelocity(Leg leg, double theta1_dot, double theta2_dot) const {
  const LegChain& c = legs_[static_cast<int>(leg)];
  // Hip and knee axes are parallel and the knee origin is not rotated (CheckPlanarLeg), so both
  // rates turn about the hip axis expressed in the trunk.
  return c.T_trunk_hip.linear() * c.hip_axis * (theta1_dot + theta2_dot);
}

bool LegKinematics::Inverse(Leg leg, const Eigen::Vector3d& p_trunk_foot, double* theta1,
                            double* theta2) const {
  const LegChain& c = chain(leg);
  // Sagittal coordinates relative to the hip: forward x and downward depth. With the axis along
  // -y a positive angle swings the link forward: foot = (l1 s1 + l2 s12, -(l1 c1 + l2 c12)).
  const double sign = -c.hip_axis.y();  // +1 for axis -y, -1 for axis +y
  const Eigen::Vector3d d = p_trunk_foot - c.T_trunk_hip.translation();
  const double x = d.x(), depth = -d.z();
  const double r_max = l1_ + l2_, r_min = std::abs(l1_ - l2_);
  double r = std::hypot(x, depth);
  bool ok = true;
  if (r > r_max) { r = r_max; ok = false; }
  if (r < r_min + 1e-9) { r = r_min + 1e-9; ok = false; }
  const double cos2 = std::clamp((r * r - l1_ * l1_ - l2_ * l2_) / (2 * l1_ * l2_), -1.0, 1.0);
  const double q2 = std::acos(cos2);  // knee backward: theta2 >= 0
  const double q1 = std::atan2(x, depth) - std::atan2(l2_ * std::sin(q2), l1_ + l2_ * std::cos(q2));
  double t1 = sign * q1, t2 = sign * q2;
  if (t1 < c.hip_lower || t1 > c.hip_upper || t2 < c.knee_lower || t2 > c.knee_upper) ok = false;
  *theta1 = std::clamp(t1, c.hip_lower, c.hip_upper);
  *theta2 = std::clamp(t2, c.knee_lower, c.knee_upper);
  return ok;
}

}  // namespace viqu::kin

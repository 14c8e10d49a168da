#include "sim/world.h"

#include <cmath>

#include "common/errors.h"
#include "sim/scene_composer.h"
#include "sim/terrain.h"

namespace viqu::sim {
namespace {

// MuJoCo cameras look along -z with y up; the optical frame looks along +z with y down.
const Eigen::Matrix3d kR_mjcam_optical = Eigen::Vector3d(1, -1, -1).asDiagonal();

const char* kJointSuffix[kJointsPerLeg] = {"_hip", "_knee"};

Eigen::Matrix3d Mat3(const mjtNum* m) {
  Eigen::Matrix3d R;
  R << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  return R;
}

}  // namespace

World::World(const Scenario& s, const std::array<double, kNumJoints>& q_stand, double stand_height_m) {
  SceneHeader header;
  header.timestep_s = s.physics_dt_s;
  header.offscreen_width = std::max(s.sensors.camera.width, 64);
  header.offscreen_height = std::max(s.sensors.camera.height, 64);
  xml_ = ComposeSceneXml(s, header, {ObstaclesXml(s.obstacles), TerrainXml(s.terrain)});
  // MuJoCo names a line of the composed scene: the error names the world or robot file's own line.
  model_ = LoadModelString(xml_, s.source_file.empty() ? s.name : s.source_file,
                           [this](int line) { return SourceOfComposedLine(xml_, line); });
  mjModel* m = model_.get();
  ApplyFloorFriction(m, s.terrain.friction, s.world);
  timestep_ns_ = std::llround(m->opt.timestep * 1e9);

  const std::string what = s.robot.model;
  trunk_body_ = MjIdOrThrow(m, mjOBJ_BODY, "trunk", what);
  disturbances_ = s.disturbances;
  cam_left_ = MjIdOrThrow(m, mjOBJ_CAMERA, "cam_left", what);
  cam_right_ = MjIdOrThrow(m, mjOBJ_CAMERA, "cam_right", what);
  accel_adr_ = m->sensor_adr[MjIdOrThrow(m, mjOBJ_SENSOR, "imu_accel", what)];
  gyro_adr_ = m->sensor_adr[MjIdOrThrow(m, mjOBJ_SENSOR, "imu_gyro", what)];
  for (int leg = 0; leg < kNumLegs; ++leg) {
    const std::string prefix = LegName(static_cast<Leg>(leg));
    for (int j = 0; j < kJointsPerLeg; ++j) {
      const std::string name = prefix + kJointSuffix[j];
      const int jid = MjIdOrThrow(m, mjOBJ_JOINT, name, what);
      qpos_adr_[2 * leg + j] = m->jnt_qposadr[jid];
      dof_adr_[2 * leg + j] = m->jnt_dofadr[jid];
      actuator_[2 * leg + j] = MjIdOrThrow(m, mjOBJ_ACTUATOR, name, what);
    }
    foot_geom_[leg] = MjIdOrThrow(m, mjOBJ_GEOM, prefix + "_foot", what);
    foot_site_[leg] = MjIdOrThrow(m, mjOBJ_SITE, prefix + "_foot", what);
  }
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = m->geom_bodyid[g];
    if (b == trunk_body_ || MjName(m, mjOBJ_BODY, b) == "rat/head") trunk_geoms_.push_back(g);
  }

  // Stereo rig from the scenario: fovy and baseline (cameras symmetric about the head centre).
  const double fovy = s.sensors.camera.fovy_deg;
  m->cam_fovy[cam_left_] = m->cam_fovy[cam_right_] = fovy;
  const double y_mid = 0.5 * (m->cam_pos[3 * cam_left_ + 1] + m->cam_pos[3 * cam_right_ + 1]);
  m->cam_pos[3 * cam_left_ + 1] = y_mid + 0.5 * s.sensors.camera.baseline_m;
  m->cam_pos[3 * cam_right_ + 1] = y_mid - 0.5 * s.sensors.camera.baseline_m;

  obstacles_ = std::make_unique<ObstacleSet>(m, s.obstacles);
  data_.reset(mj_makeData(m));
  mjData* d = data_.get();
  const int root_qpos = m->jnt_qposadr[m->body_jntadr[trunk_body_]];
  const double yaw = s.robot.start.yaw_deg * M_PI / 180.0;
  d->qpos[root_qpos + 0] = s.robot.start.xy[0];
  d->qpos[root_qpos + 1] = s.robot.start.xy[1];
  d->qpos[root_qpos + 2] = stand_height_m;
  d->qpos[root_qpos + 3] = std::cos(yaw / 2);
  d->qpos[root_qpos + 4] = 0;
  d->qpos[root_qpos + 5] = 0;
  d->qpos[root_qpos + 6] = std::sin(yaw / 2);
  for (int i = 0; i < kNumJoints; ++i) d->qpos[qpos_adr_[i]] = q_stand[i];
  SetJointTargets(q_stand);
  obstacles_->Apply(m, d, 0.0);
  mj_forward(m, d);
}

void World::SetJointTargets(const std::array<double, kNumJoints>& q) {
  for (int i = 0; i < kNumJoints; ++i) data_->ctrl[actuator_[i]] = q[i];
}

void World::Step() {
  obstacles_->Apply(model_.get(), data_.get(), data_->time);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const Disturbance& d : disturbances_) {
    if (data_->time >= d.t_s && data_->time < d.t_s + d.duration_s) force += Eigen::Vector3d(d.force_n.data());
  }
  mjtNum* xfrc = data_->xfrc_applied + 6 * trunk_body_;  // force (3) then torque (3), world frame
  for (int k = 0; k < 3; ++k) xfrc[k] = force[k];
  mj_step(model_.get(), data_.get());
  accel_sum_ += TrueAccel();
  gyro_sum_ += TrueGyro();
  ++imu_steps_;
  const std::array<double, kNumJoints> tau = JointTorques();
  for (int i = 0; i < kNumJoints; ++i) torque_sum_[i] += tau[i];
  ++torque_steps_;
}

std::array<double, kNumJoints> World::JointTorques() const {
  std::array<double, kNumJoints> tau{};
  for (int i = 0; i < kNumJoints; ++i) tau[i] = data_->qfrc_actuator[dof_adr_[i]];
  return tau;
}

std::array<double, kNumJoints> World::TakeJointTorqueMean() {
  std::array<double, kNumJoints> mean = JointTorques();
  if (torque_steps_ > 0) {
    for (int i = 0; i < kNumJoints; ++i) mean[i] = torque_sum_[i] / torque_steps_;
  }
  torque_sum_.fill(0.0);
  torque_steps_ = 0;
  return mean;
}

World::ImuMean World::TakeImuMean() {
  ImuMean m{TrueAccel(), TrueGyro()};
  if (imu_steps_ > 0) {
    m.accel_i = accel_sum_ / imu_steps_;
    m.gyro_i = gyro_sum_ / imu_steps_;
  }
  accel_sum_.setZero();
  gyro_sum_.setZero();
  imu_steps_ = 0;
  return m;
}

int64_t World::time_ns() const { return std::llround(data_->time * 1e9); }

GroundTruthState World::GroundTruth() const {
  const mjData* d = data_.get();
  GroundTruthState gt;
  gt.t_ns = time_ns();
  gt.T_w_body.t_ns = gt.T_w_cam.t_ns = gt.t_ns;
  gt.T_w_body.p_w_x = Eigen::Map<const Eigen::Vector3d>(d->xpos + 3 * trunk_body_);
  gt.T_w_body.q_w_x = Eigen::Quaterniond(d->xquat[4 * trunk_body_], d->xquat[4 * trunk_body_ + 1],
                                         d->xquat[4 * trunk_body_ + 2], d->xquat[4 * trunk_body_ + 3]);
  gt.T_w_cam.p_w_x = Eigen::Map<const Eigen::Vector3d>(d->cam_xpos + 3 * cam_left_);
  gt.T_w_cam.q_w_x = Eigen::Quaterniond(Mat3(d->cam_xmat + 9 * cam_left_) * kR_mjcam_optical).normalized();
  mjtNum vel[6];
  mj_objectVelocity(model_.get(), d, mjOBJ_BODY, trunk_body_, vel, 0);
  gt.vel_w_body = Eigen::Vector3d(vel[3], vel[4], vel[5]);
  return gt;
}

std::array<double, kNumJoints> World::JointPositions() const {
  std::array<double, kNumJoints> q{};
  for (int i = 0; i < kNumJoints; ++i) q[i] = data_->qpos[qpos_adr_[i]];
  return q;
}

std::array<double, kNumJoints> World::JointVelocities() const {
  std::array<double, kNumJoints> qd{};
  for (int i = 0; i < kNumJoints; ++i) qd[i] = data_->qvel[dof_adr_[i]];
  return qd;
}

bool World::IsRobotGeom(int geom) const {
  return model_->body_rootid[model_->geom_bodyid[geom]] == model_->body_rootid[trunk_body_];
}

int World::FootOfContact(int contact) const {
  const mjContact& con = data_->contact[contact];
  for (int leg = 0; leg < kNumLegs; ++leg) {
    if ((con.geom1 == foot_geom_[leg] && !IsRobotGeom(con.geom2)) ||
        (con.geom2 == foot_geom_[leg] && !IsRobotGeom(con.geom1))) {
      return leg;
    }
  }
  return -1;
}

std::array<bool, kNumLegs> World::FootContacts() const {
  std::array<bool, kNumLegs> c{};
  for (int i = 0; i < data_->ncon; ++i) {
    const int leg = FootOfContact(i);
    if (leg >= 0) c[leg] = true;
  }
  return c;
}

std::array<double, kNumLegs> World::FootNormalForces() const {
  std::array<double, kNumLegs> f{};
  for (int i = 0; i < data_->ncon; ++i) {
    const int leg = FootOfContact(i);
    if (leg < 0) continue;
    mjtNum force[6];
    mj_contactForce(model_.get(), data_.get(), i, force);  // contact frame: force[0] is the normal force
    f[leg] += force[0];
  }
  return f;
}

Eigen::Vector3d World::FootPositionWorld(Leg leg) const {
  return Eigen::Map<const Eigen::Vector3d>(data_->site_xpos + 3 * foot_site_[static_cast<int>(leg)]);
}

Eigen::Vector3d World::FootVelocityWorld(Leg leg) const {
  mjtNum vel[6];
  mj_objectVelocity(model_.get(), data_.get(), mjOBJ_SITE, foot_site_[static_cast<int>(leg)], vel, 0);
  return Eigen::Vector3d(vel[3], vel[4], vel[5]);
}

Eigen::Vector3d World::FootSoleVelocityWorld(Leg leg) const {
  const int i = static_cast<int>(leg);
  mjtNum vel[6];  // [angular; linear] at the site centre, world orientation
  mj_objectVelocity(model_.get(), data_.get(), mjOBJ_SITE, foot_site_[i], vel, 0);
  const Eigen::Vector3d w(vel[0], vel[1], vel[2]), v(vel[3], vel[4], vel[5]);
  const Eigen::Vector3d r_sole(0, 0, -model_->geom_size[3 * foot_geom_[i]]);  // centre to lowest point
  return v + w.cross(r_sole);
}

Eigen::Vector3d World::TrueAccel() const {
  return Eigen::Map<const Eigen::Vector3d>(data_->sensordata + accel_adr_);
}

Eigen::Vector3d World::TrueGyro() const {
  return Eigen::Map<const Eigen::Vector3d>(data_->sensordata + gyro_adr_);
}

bool World::TrunkTouchesGround() const {
  const mjData* d = data_.get();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    for (int g : trunk_geoms_) {
      if ((con.geom1 == g && !IsRobotGeom(con.geom2)) || (con.geom2 == g && !IsRobotGeom(con.geom1))) {
        return true;
      }
    }
  }
  return false;
}

double World::TrunkTiltRad() const {
  const double zz = data_->xmat[9 * trunk_body_ + 8];
  return std::acos(std::clamp(zz, -1.0, 1.0));
}

Eigen::Isometry3d World::T_body_cam(bool right) const {
  const int cam = right ? cam_right_ : cam_left_;
  const mjModel* m = model_.get();
  Eigen::Isometry3d T_trunk_cambody = Eigen::Isometry3d::Identity();
  // The camera's parent body (the head) sits in the trunk at a fixed offset.
  const int body = m->cam_bodyid[cam];
  if (body != trunk_body_) {
    T_trunk_cambody.translation() = Eigen::Map<const Eigen::Vector3d>(m->body_pos + 3 * body);
    T_trunk_cambody.linear() = Eigen::Quaterniond(m->body_quat[4 * body], m->body_quat[4 * body + 1],
                                                  m->body_quat[4 * body + 2], m->body_quat[4 * body + 3])
                                   .toRotationMatrix();
  }
  Eigen::Isometry3d T_cambody_cam = Eigen::Isometry3d::Identity();
  T_cambody_cam.translation() = Eigen::Map<const Eigen::Vector3d>(m->cam_pos + 3 * cam);
  T_cambody_cam.linear() = Eigen::Quaterniond(m->cam_quat[4 * cam], m->cam_quat[4 * cam + 1],
                                              m->cam_quat[4 * cam + 2], m->cam_quat[4 * cam + 3])
                               .toRotationMatrix() * kR_mjcam_optical;
  return T_trunk_cambody * T_cambody_cam;
}

}  // namespace viqu::sim

// The URDF (kinematic truth for leg odometry) and the MJCF (what MuJoCo simulates) describe the
// same robot: forward kinematics from the URDF puts every foot where MuJoCo's foot site is.
#include <random>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "kinematics/leg_kinematics.h"
#include "sim/mujoco_handles.h"
#include "random_vector.h"

namespace viqu {
namespace {

const std::string kRatDir = std::string(VIQU_SOURCE_DIR) + "/models/rat/";

class KinematicsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::TakeMujocoWarnings();
    model_ = sim::LoadModelFile(kRatDir + "rat.xml");
    data_.reset(mj_makeData(model_.get()));
    ASSERT_TRUE(sim::TakeMujocoWarnings().empty());
  }
  const kin::LegKinematics kin_ = kin::LegKinematics::FromUrdfFile(kRatDir + "rat.urdf");
  sim::ModelPtr model_;
  sim::DataPtr data_;
};

TEST_F(KinematicsTest, UrdfForwardKinematicsMatchesMujocoFootSites) {
  const mjModel* m = model_.get();
  mjData* d = data_.get();
  const int trunk = mj_name2id(m, mjOBJ_BODY, "trunk");
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 200; ++trial) {
    // Random trunk pose too, so the comparison happens in the trunk frame.
    std::uniform_real_distribution<double> u(-1, 1);
    d->qpos[0] = u(rng);
    d->qpos[1] = u(rng);
    d->qpos[2] = 0.5 + u(rng) * 0.2;
    const Eigen::Vector3d axis = testing::RandomVector(u, rng);  // drawn before the angle (random_vector.h)
    const double angle = u(rng) * M_PI;
    Eigen::Quaterniond q(Eigen::AngleAxisd(angle, axis.normalized()));
    d->qpos[3] = q.w(); d->qpos[4] = q.x(); d->qpos[5] = q.y(); d->qpos[6] = q.z();
    std::array<double, kNumJoints> angles{};
    for (int leg = 0; leg < kNumLegs; ++leg) {
      const auto& c = kin_.chain(static_cast<Leg>(leg));
      angles[2 * leg] = std::uniform_real_distribution<double>(c.hip_lower, c.hip_upper)(rng);
      angles[2 * leg + 1] = std::uniform_real_distribution<double>(c.knee_lower, c.knee_upper)(rng);
      const int jh = mj_name2id(m, mjOBJ_JOINT, (std::string(LegName(static_cast<Leg>(leg))) + "_hip").c_str());
      const int jk = mj_name2id(m, mjOBJ_JOINT, (std::string(LegName(static_cast<Leg>(leg))) + "_knee").c_str());
      d->qpos[m->jnt_qposadr[jh]] = angles[2 * leg];
      d->qpos[m->jnt_qposadr[jk]] = angles[2 * leg + 1];
    }
    mj_kinematics(m, d);
    const Eigen::Vector3d p_w_trunk(d->xpos + 3 * trunk);
    Eigen::Matrix3d R_w_trunk;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R_w_trunk(r, c) = d->xmat[9 * trunk + 3 * r + c];
    for (int leg = 0; leg < kNumLegs; ++leg) {
      const int site = mj_name2id(m, mjOBJ_SITE, (std::string(LegName(static_cast<Leg>(leg))) + "_foot").c_str());
      const Eigen::Vector3d p_w_foot(d->site_xpos + 3 * site);
      const Eigen::Vector3d mujoco_in_trunk = R_w_trunk.transpose() * (p_w_foot - p_w_trunk);
      const Eigen::Vector3d urdf_in_trunk = kin_.FootInTrunk(static_cast<Leg>(leg), angles[2 * leg], angles[2 * leg + 1]);
      EXPECT_LT((mujoco_in_trunk - urdf_in_trunk).norm(), 1e-6) << "leg " << LegName(static_cast<Leg>(leg)) << " trial " << trial;
    }
  }
}

TEST_F(KinematicsTest, UrdfAndMjcfHaveTheSameMassAndJointLimits) {
  const mjModel* m = model_.get();
  double mass = 0;
  for (int b = 1; b < m->nbody; ++b) mass += m->body_mass[b];
  EXPECT_NEAR(mass, kin_.total_mass(), 1e-9);
  for (int leg = 0; leg < kNumLegs; ++leg) {
    const auto& c = kin_.chain(static_cast<Leg>(leg));
    const int jh = mj_name2id(m, mjOBJ_JOINT, (std::string(LegName(static_cast<Leg>(leg))) + "_hip").c_str());
    const int jk = mj_name2id(m, mjOBJ_JOINT, (std::string(LegName(static_cast<Leg>(leg))) + "_knee").c_str());
    EXPECT_NEAR(m->jnt_range[2 * jh], c.hip_lower, 1e-9);
    EXPECT_NEAR(m->jnt_range[2 * jh + 1], c.hip_upper, 1e-9);
    EXPECT_NEAR(m->jnt_range[2 * jk], c.knee_lower, 1e-9);
    EXPECT_NEAR(m->jnt_range[2 * jk + 1], c.knee_upper, 1e-9);
  }
}

TEST_F(KinematicsTest, InverseKinematicsRoundTrips) {
  std::mt19937_64 rng(7);
  for (int leg = 0; leg < kNumLegs; ++leg) {
    const Leg l = static_cast<Leg>(leg);
    for (int trial = 0; trial < 200; ++trial) {
      const double t1 = std::uniform_real_distribution<double>(-0.8, 0.8)(rng);
      const double t2 = std::uniform_real_distribution<double>(0.2, 2.2)(rng);
      const Eigen::Vector3d p = kin_.FootInTrunk(l, t1, t2);
      double s1 = 0, s2 = 0;
      ASSERT_TRUE(kin_.Inverse(l, p, &s1, &s2));
      EXPECT_NEAR(s1, t1, 1e-9);
      EXPECT_NEAR(s2, t2, 1e-9);
    }
  }
}

TEST_F(KinematicsTest, JacobianMatchesFiniteDifferences) {
  const double h = 1e-6;
  for (int leg = 0; leg < kNumLegs; ++leg) {
    const Leg l = static_cast<Leg>(leg);
    const double t1 = 0.3, t2 = 1.1;
    const Eigen::Matrix<double, 3, 2> J = kin_.FootJacobian(l, t1, t2);
    const Eigen::Vector3d d1 = (kin_.FootInTrunk(l, t1 + h, t2) - kin_.FootInTrunk(l, t1 - h, t2)) / (2 * h);
    const Eigen::Vector3d d2 = (kin_.FootInTrunk(l, t1, t2 + h) - kin_.FootInTrunk(l, t1, t2 - h)) / (2 * h);
    EXPECT_LT((J.col(0) - d1).norm(), 1e-8);
    EXPECT_LT((J.col(1) - d2).norm(), 1e-8);
  }
}

TEST(KinematicsInput, RejectsAUrdfWithoutLegs) {
  EXPECT_THROW(kin::LegKinematics::FromUrdfString("<robot name=\"x\"><link name=\"trunk\"/></robot>", "inline"),
               InputError);
  EXPECT_THROW(kin::LegKinematics::FromUrdfFile("/nonexistent/rat.urdf"), InputError);
}

}  // namespace
}  // namespace viqu

// Leg odometry + IMU: the cost of one IMU sample and one encoder reading through the attitude
// filter and the 18-state Kalman filter (issue 8 target: <= 0.05 ms per IMU sample). The robot
// stands on the URDF's legs with noisy sensors; all four feet in stance (the most updates, and
// all six stance pairs of the yaw-bias estimator). Argument 1: the estimator on (default), 0: off.
// BM_FootForceSample adds the foot-force estimate from the servos' torques (issue 55: the whole
// update, KF + forces + contact + slip, <= 0.05 ms per sample); the slip decision and the contact
// are inside the first.
#include <random>

#include <benchmark/benchmark.h>

#include "kinematics/leg_kinematics.h"
#include "slam/lo/foot_force.h"
#include "slam/lo/leg_odometry.h"

namespace viqu {
namespace {

// The joint angles of the robot standing with each foot 69 mm below its hip.
std::array<double, kNumJoints> StandingAngles(const kin::LegKinematics& kin) {
  std::array<double, kNumJoints> q{};
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg leg = static_cast<Leg>(i);
    const Eigen::Vector3d hip = kin.chain(leg).T_trunk_hip.translation();
    kin.Inverse(leg, Eigen::Vector3d(hip.x(), hip.y(), -0.069), &q[2 * i], &q[2 * i + 1]);
  }
  return q;
}

void BM_LegOdometrySample(benchmark::State& state) {
  const kin::LegKinematics kin = kin::LegKinematics::FromUrdfFile(std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.urdf");
  slam::LegOdometrySettings settings;
  settings.contact = "schedule";
  if (state.range(0) == 0) settings.yaw_bias_initial_std = 0;
  lo::LegOdometry lo(settings, kin);
  lo.Start(0, Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.075)));
  const std::array<double, kNumJoints> q = StandingAngles(kin);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> n(0, 1);
  int64_t t = 0;
  for (auto _ : state) {
    t += 5'000'000;
    ImuSample imu;
    imu.t_ns = t;
    // One draw per statement: the order of draws inside one call's arguments is up to the compiler.
    const double az = n(rng), ay = n(rng), ax = n(rng), gz = n(rng), gy = n(rng), gx = n(rng);
    imu.accel_i = Eigen::Vector3d(0.02 * ax, 0.02 * ay, 9.81 + 0.02 * az);
    imu.gyro_i = Eigen::Vector3d(0.002 * gx, 0.002 * gy, 0.002 * gz);
    lo.AddImu(imu);
    lo.AddContact(ContactReading{t, {true, true, true, true}});
    JointState js;
    js.t_ns = t;
    for (int j = 0; j < kNumJoints; ++j) js.position_rad[j] = q[j] + 0.001 * n(rng);
    lo.AddJoints(js);
    benchmark::DoNotOptimize(lo.T_w_body());
  }
}
BENCHMARK(BM_LegOdometrySample)->Arg(1)->Arg(0);

void BM_FootForceSample(benchmark::State& state) {
  const kin::LegKinematics kin = kin::LegKinematics::FromUrdfFile(std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.urdf");
  lo::FootForceEstimator est(kin, lo::FootForceModel{}, lo::ForceAlignment::kCentred);
  const std::array<double, kNumJoints> q = StandingAngles(kin);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> n(0, 1);
  int64_t t = 0;
  for (auto _ : state) {
    t += 5'000'000;
    JointState js;
    js.t_ns = t;
    js.has_torque = true;
    for (int j = 0; j < kNumJoints; ++j) {
      js.position_rad[j] = q[j] + 0.001 * n(rng);
      js.velocity_rad_s[j] = 0.4 * n(rng);
      js.torque_nm[j] = 0.1 + 0.005 * n(rng);
    }
    benchmark::DoNotOptimize(est.Update(js, Eigen::Vector3d(0, 0, -9.81)));
  }
}
BENCHMARK(BM_FootForceSample);

}  // namespace
}  // namespace viqu

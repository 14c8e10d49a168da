#pragma once
// IMU sensor model: white noise plus bias random walk on top of the true specific force and
// angular velocity. Pure C++ on plain inputs (no MuJoCo), so it is unit tested on its own; the
// simulator feeds it the readings of MuJoCo's `imu_accel` and `imu_gyro` sensors.
#include <cstdint>
#include <optional>
#include <random>

#include <Eigen/Core>

#include "scenario/scenario.h"
#include "slam/measurements/imu_sample.h"

namespace viqu::sim {

// Initial biases of the IMU. ImuConfig (the scenario) has no key for them: a real IMU is switched
// on with a bias that the estimator must find, so by default each axis is drawn once from the
// seeded generator, N(0, std^2). Setting a value fixes it instead (tests, replays).
struct ImuBiasOptions {
  std::optional<Eigen::Vector3d> accel_bias_i;  // fixed initial accel bias, IMU frame (m/s^2)
  std::optional<Eigen::Vector3d> gyro_bias_i;   // fixed initial gyro bias, IMU frame (rad/s)
  double accel_bias_std = 0.02;   // std of the drawn initial accelerometer bias per axis (m/s^2)
  double gyro_bias_std = 0.002;   // std of the drawn initial gyro bias per axis (rad/s)
};

// Measurement model, per axis, for a reading at time t_k:
//   b_k = b_{k-1} + N(0, walk^2 * dt_k)      bias random walk, dt_k = t_k - t_{k-1} (s)
//   y_k = truth_k + b_k + N(0, noise^2)      noise = white noise std per sample
// with walk in continuous-time units (m/s^2/sqrt(s), rad/s/sqrt(s)), so the bias variance grows as
// walk^2 * t independently of the rate. The first reading uses dt = 1 / rate_hz.
// The bias is updated before the reading, so accel_bias()/gyro_bias() after Measure() return the
// bias contained in the reading just returned.
class ImuModel {
 public:
  // Throws viqu::InputError for a non-positive rate or negative noise / walk / bias std.
  ImuModel(const viqu::ImuConfig& config, uint64_t seed, const ImuBiasOptions& bias = {});

  // One reading. true_accel_i: specific force in the IMU frame (m/s^2), gravity included (MuJoCo's
  // accelerometer: +9.81 on z when level and at rest); true_gyro_i: angular velocity in the IMU
  // frame (rad/s). Throws viqu::InputError for non-finite inputs or a timestamp that does not
  // increase (t_ns <= previous t_ns); a rejected call leaves the model unchanged.
  viqu::ImuSample Measure(int64_t t_ns, const Eigen::Vector3d& true_accel_i,
                          const Eigen::Vector3d& true_gyro_i);

  Eigen::Vector3d accel_bias() const { return accel_bias_i_; }  // current accel bias (m/s^2)
  Eigen::Vector3d gyro_bias() const { return gyro_bias_i_; }    // current gyro bias (rad/s)

 private:
  Eigen::Vector3d Gaussian3(double std);  // three independent N(0, std^2) draws

  viqu::ImuConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Eigen::Vector3d accel_bias_i_ = Eigen::Vector3d::Zero();  // (m/s^2)
  Eigen::Vector3d gyro_bias_i_ = Eigen::Vector3d::Zero();   // (rad/s)
  std::optional<int64_t> last_t_ns_;  // time of the previous reading (ns); none before the first
};

}  // namespace viqu::sim

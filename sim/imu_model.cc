#include "sim/imu_model.h"

#include <cmath>
#include <sstream>
#include <string>

#include "common/errors.h"

namespace viqu::sim {
namespace {

void RequireNonNegative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "ImuModel: " << name << " must be finite and >= 0, got " << value;
    throw viqu::InputError(msg.str());
  }
}

// `when` says where the vector came from, e.g. "at t_ns 5000000".
void RequireFinite(const Eigen::Vector3d& v, const char* name, const std::string& when) {
  if (!v.allFinite()) {
    std::ostringstream msg;
    msg << "ImuModel: non-finite " << name << " (" << v.transpose() << ") " << when;
    throw viqu::InputError(msg.str());
  }
}

}  // namespace

ImuModel::ImuModel(const viqu::ImuConfig& config, uint64_t seed, const ImuBiasOptions& bias)
    : config_(config), rng_(seed) {
  if (!(config.rate_hz > 0.0) || !std::isfinite(config.rate_hz)) {
    std::ostringstream msg;
    msg << "ImuModel: rate_hz must be finite and > 0, got " << config.rate_hz;
    throw viqu::InputError(msg.str());
  }
  RequireNonNegative(config.accel_noise, "accel_noise");
  RequireNonNegative(config.gyro_noise, "gyro_noise");
  RequireNonNegative(config.accel_bias_walk, "accel_bias_walk");
  RequireNonNegative(config.gyro_bias_walk, "gyro_bias_walk");
  RequireNonNegative(bias.accel_bias_std, "accel_bias_std");
  RequireNonNegative(bias.gyro_bias_std, "gyro_bias_std");
  if (bias.accel_bias_i) {
    RequireFinite(*bias.accel_bias_i, "initial accel bias", "in ImuBiasOptions");
  }
  if (bias.gyro_bias_i) {
    RequireFinite(*bias.gyro_bias_i, "initial gyro bias", "in ImuBiasOptions");
  }
  // Always draw both initial biases, even when fixed ones are given, so that the noise stream
  // that follows is the same whichever option is used.
  const Eigen::Vector3d drawn_accel = Gaussian3(bias.accel_bias_std);
  const Eigen::Vector3d drawn_gyro = Gaussian3(bias.gyro_bias_std);
  accel_bias_i_ = bias.accel_bias_i ? *bias.accel_bias_i : drawn_accel;
  gyro_bias_i_ = bias.gyro_bias_i ? *bias.gyro_bias_i : drawn_gyro;
}

Eigen::Vector3d ImuModel::Gaussian3(double std) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = std * normal_(rng_);
  return v;
}

viqu::ImuSample ImuModel::Measure(int64_t t_ns, const Eigen::Vector3d& true_accel_i,
                                  const Eigen::Vector3d& true_gyro_i) {
  if (!true_accel_i.allFinite() || !true_gyro_i.allFinite()) {  // format only on failure
    const std::string when = "at t_ns " + std::to_string(t_ns);
    RequireFinite(true_accel_i, "true_accel_i", when);
    RequireFinite(true_gyro_i, "true_gyro_i", when);
  }
  if (last_t_ns_ && t_ns <= *last_t_ns_) {
    std::ostringstream msg;
    msg << "ImuModel: timestamps must increase, got t_ns " << t_ns << " after " << *last_t_ns_;
    throw viqu::InputError(msg.str());
  }
  const double dt_s = last_t_ns_ ? 1e-9 * static_cast<double>(t_ns - *last_t_ns_)
                                 : 1.0 / config_.rate_hz;
  last_t_ns_ = t_ns;

  const double sqrt_dt = std::sqrt(dt_s);
  accel_bias_i_ += Gaussian3(config_.accel_bias_walk * sqrt_dt);
  gyro_bias_i_ += Gaussian3(config_.gyro_bias_walk * sqrt_dt);

  viqu::ImuSample sample;
  sample.t_ns = t_ns;
  sample.accel_i = true_accel_i + accel_bias_i_ + Gaussian3(config_.accel_noise);
  sample.gyro_i = true_gyro_i + gyro_bias_i_ + Gaussian3(config_.gyro_noise);
  return sample;
}

}  // namespace viqu::sim

#include "sim/torque_model.h"

#include <cmath>
#include <sstream>

#include "common/errors.h"

namespace viqu::sim {
namespace {

void RequireNonNegative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "TorqueModel: " << name << " must be finite and >= 0, got " << value;
    throw viqu::InputError(msg.str());
  }
}

}  // namespace

TorqueModel::TorqueModel(const viqu::JointsConfig& config, uint64_t seed) : config_(config), rng_(seed) {
  if (!(config.rate_hz > 0.0) || !std::isfinite(config.rate_hz)) {
    std::ostringstream msg;
    msg << "TorqueModel: rate_hz must be finite and > 0, got " << config.rate_hz;
    throw viqu::InputError(msg.str());
  }
  RequireNonNegative(config.torque_noise_nm, "torque_noise_nm");
  RequireNonNegative(config.torque_resolution_nm, "torque_resolution_nm");
  RequireNonNegative(config.torque_bias_nm, "torque_bias_nm");
  RequireNonNegative(config.torque_delay_s, "torque_delay_s");
  delay_readings_ = static_cast<int>(std::lround(config.torque_delay_s * config.rate_hz));
  for (double& b : bias_nm_) b = config_.torque_bias_nm * normal_(rng_);
}

double TorqueModel::Quantise(double x) const {
  if (config_.torque_resolution_nm <= 0.0) return x;
  return config_.torque_resolution_nm * std::round(x / config_.torque_resolution_nm);
}

std::array<double, viqu::kNumJoints> TorqueModel::Measure(const std::array<double, viqu::kNumJoints>& tau) {
  for (int j = 0; j < viqu::kNumJoints; ++j) {
    if (!std::isfinite(tau[j])) {
      std::ostringstream msg;
      msg << "TorqueModel: non-finite torque[" << j << "] = " << tau[j];
      throw viqu::InputError(msg.str());
    }
  }
  if (history_.empty()) history_.assign(static_cast<size_t>(delay_readings_) + 1, tau);
  history_.push_back(tau);
  history_.pop_front();
  const std::array<double, viqu::kNumJoints>& delayed = history_.front();
  std::array<double, viqu::kNumJoints> out{};
  for (int j = 0; j < viqu::kNumJoints; ++j) {
    out[j] = Quantise(delayed[j] + bias_nm_[j] + config_.torque_noise_nm * normal_(rng_));
  }
  return out;
}

}  // namespace viqu::sim

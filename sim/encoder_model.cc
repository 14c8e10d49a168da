#include "sim/encoder_model.h"

#include <cmath>
#include <sstream>

#include "common/errors.h"

namespace viqu::sim {
namespace {

void RequireNonNegative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "EncoderModel: " << name << " must be finite and >= 0, got " << value;
    throw viqu::InputError(msg.str());
  }
}

void RequireFinite(const std::array<double, viqu::kNumJoints>& v, const char* name, int64_t t_ns) {
  for (int j = 0; j < viqu::kNumJoints; ++j) {
    if (!std::isfinite(v[j])) {
      std::ostringstream msg;
      msg << "EncoderModel: non-finite " << name << "[" << j << "] = " << v[j] << " at t_ns "
          << t_ns;
      throw viqu::InputError(msg.str());
    }
  }
}

}  // namespace

EncoderModel::EncoderModel(const viqu::JointsConfig& config, uint64_t seed)
    : config_(config), rng_(seed) {
  if (!(config.rate_hz > 0.0) || !std::isfinite(config.rate_hz)) {
    std::ostringstream msg;
    msg << "EncoderModel: rate_hz must be finite and > 0, got " << config.rate_hz;
    throw viqu::InputError(msg.str());
  }
  RequireNonNegative(config.noise_rad, "noise_rad");
  RequireNonNegative(config.resolution_rad, "resolution_rad");
}

double EncoderModel::Quantise(double x) const {
  if (config_.resolution_rad <= 0.0) return x;
  return config_.resolution_rad * std::round(x / config_.resolution_rad);
}

viqu::JointState EncoderModel::Measure(int64_t t_ns, const std::array<double, viqu::kNumJoints>& q,
                                       const std::array<double, viqu::kNumJoints>& qd,
                                       const std::array<bool, viqu::kNumLegs>& contact) {
  RequireFinite(q, "q", t_ns);
  RequireFinite(qd, "qd", t_ns);
  if (last_t_ns_ && t_ns <= *last_t_ns_) {
    std::ostringstream msg;
    msg << "EncoderModel: timestamps must increase, got t_ns " << t_ns << " after " << *last_t_ns_;
    throw viqu::InputError(msg.str());
  }

  viqu::JointState state;
  state.t_ns = t_ns;
  state.contact = contact;
  for (int j = 0; j < viqu::kNumJoints; ++j) {
    state.position_rad[j] = Quantise(q[j] + config_.noise_rad * normal_(rng_));
  }
  if (last_t_ns_) {
    const double dt_s = 1e-9 * static_cast<double>(t_ns - *last_t_ns_);
    for (int j = 0; j < viqu::kNumJoints; ++j) {
      state.velocity_rad_s[j] = (state.position_rad[j] - last_position_rad_[j]) / dt_s;
    }
  } else {
    state.velocity_rad_s = qd;
  }
  last_t_ns_ = t_ns;
  last_position_rad_ = state.position_rad;
  return state;
}

}  // namespace viqu::sim

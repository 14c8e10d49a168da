#include "controllers/gait_controller.h"

#include <algorithm>
#include <cmath>

namespace viqu::ctrl {
namespace {

double SlewTo(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}

// Cubic Hermite from x0 to x1 over s in [0, 1] with slope m (dx/ds) at both ends. A swing foot
// leaves and meets the ground moving with it (m = ground speed in the trunk frame times the swing
// duration), so neither lift-off nor touch-down drags the foot.
double Hermite(double x0, double x1, double m, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * m + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * m;
}

constexpr double kIdleCommand = 1e-4;  // |command| below this counts as "stand still"

}  // namespace

GaitController::GaitController(const kin::LegKinematics& kin, const GaitConfig& gait,
                               const GaitControllerOptions& opt)
    : kin_(kin), schedule_(gait.type, gait.frequency_hz, gait.duty), gait_(gait), opt_(opt) {
  for (int i = 0; i < kNumLegs; ++i) targets_[i] = NominalFoot(static_cast<Leg>(i));
}

Eigen::Vector3d GaitController::NominalFoot(Leg leg) const {
  const Eigen::Vector3d hip = kin_.chain(leg).T_trunk_hip.translation();
  const double inset = hip.x() > 0 ? -opt_.inset_m : opt_.inset_m;
  return Eigen::Vector3d(hip.x() + opt_.foot_x_offset_m + inset, hip.y(),
                         -(opt_.stand_height_m - opt_.foot_radius_m));
}

std::array<double, kNumJoints> GaitController::SolveIk(const std::array<Eigen::Vector3d, kNumLegs>& feet) const {
  std::array<double, kNumJoints> q{};
  for (int i = 0; i < kNumLegs; ++i) {
    kin_.Inverse(static_cast<Leg>(i), feet[i], &q[2 * i], &q[2 * i + 1]);
  }
  return q;
}

std::array<double, kNumJoints> GaitController::StandingTargets() const {
  std::array<Eigen::Vector3d, kNumLegs> feet;
  for (int i = 0; i < kNumLegs; ++i) feet[i] = NominalFoot(static_cast<Leg>(i));
  return SolveIk(feet);
}

std::array<double, kNumJoints> GaitController::Update(double dt_s, const BodyCommand& target) {
  cmd_.forward_mps = SlewTo(cmd_.forward_mps, target.forward_mps, opt_.max_accel_mps2 * dt_s);
  cmd_.yaw_rate_rps = SlewTo(cmd_.yaw_rate_rps, target.yaw_rate_rps, opt_.max_yaw_accel_rps2 * dt_s);
  const bool idle = std::abs(target.forward_mps) < kIdleCommand && std::abs(target.yaw_rate_rps) < kIdleCommand;

  if (!stepping_ && !idle) {
    stepping_ = true;
    cycle_phase_ = 0;
    idle_time_s_ = 0;
  }
  if (stepping_) {
    // After a zero command, keep stepping for two cycles so every foot returns to its nominal
    // position, then stand.
    idle_time_s_ = idle ? idle_time_s_ + dt_s : 0;
    if (idle_time_s_ > 2.0 / schedule_.frequency_hz()) {
      bool settled = true;
      for (double x : foot_x_) settled = settled && std::abs(x) < 1e-3;
      if (settled) stepping_ = false;
    }
  }
  if (!stepping_) {
    stance_ = {true, true, true, true};
    for (int i = 0; i < kNumLegs; ++i) {
      targets_[i] = NominalFoot(static_cast<Leg>(i)) + Eigen::Vector3d(foot_x_[i], 0, 0);
    }
    return SolveIk(targets_);
  }

  cycle_phase_ += schedule_.frequency_hz() * dt_s;
  cycle_phase_ -= std::floor(cycle_phase_);
  const double half_max = 0.5 * opt_.max_stride_m;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg leg = static_cast<Leg>(i);
    const Eigen::Vector3d nominal = NominalFoot(leg);
    // Speed of the ground under this leg, seen from the trunk (turning: outer legs step longer).
    const double v_leg = cmd_.forward_mps - cmd_.yaw_rate_rps * nominal.y();
    const double touchdown_x = std::clamp(0.5 * v_leg * schedule_.stance_duration_s(), -half_max, half_max);
    const LegPhase ph = schedule_.PhaseOf(leg, cycle_phase_);
    double z = 0;
    if (ph.stance) {
      foot_x_[i] = std::clamp(foot_x_[i] - v_leg * dt_s, -half_max, half_max);
    } else {
      if (stance_[i]) liftoff_x_[i] = foot_x_[i];  // swing starts now
      foot_x_[i] = Hermite(liftoff_x_[i], touchdown_x, -v_leg * schedule_.swing_duration_s(), ph.progress);
      z = gait_.step_height_m * std::sin(M_PI * ph.progress);
    }
    stance_[i] = ph.stance;
    targets_[i] = nominal + Eigen::Vector3d(foot_x_[i], 0, z);
  }
  return SolveIk(targets_);
}

}  // namespace viqu::ctrl

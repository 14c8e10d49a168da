#include "slam/lo/yaw_bias_from_feet.h"

#include <cmath>

namespace viqu::lo {
namespace {

// Two feet closer than this horizontally give no usable direction (m): geometry, not tuning
// (the robot's feet stand 60-140 mm apart).
constexpr double kMinPairLength_m = 0.03;

}  // namespace

void YawBiasFromFeet::Reset(int64_t t_ns) {
  pairs_.fill(Pair{});
  var_ = opt_.initial_std * opt_.initial_std;
  var_t_ns_ = t_ns;
  total_ = 0;
  pieces_ = 0;
  rejected_ = 0;
  turning_ = 0;
}

void YawBiasFromFeet::TurnedBy(double dyaw) {
  for (Pair& p : pairs_) {
    if (p.active) p.turned += dyaw;
  }
}

std::optional<YawBiasFromFeet::Piece> YawBiasFromFeet::Finish(Pair* p, int64_t t_ns) {
  p->active = false;
  const double duration = (t_ns - p->t0_ns) * 1e-9;
  if (p->n < 3 || duration < opt_.min_s) return std::nullopt;
  const double sxx = p->stt - p->st * p->st / p->n;
  if (sxx <= 0) return std::nullopt;
  if (std::abs(p->rate_sum / p->n) > opt_.max_rate) {
    ++turning_;
    return std::nullopt;
  }
  const double heading_std = opt_.pair_noise_m / p->length;  // rad per reading
  return Piece{(p->sty - p->st * p->sy / p->n) / sxx, heading_std * heading_std / sxx};
}

std::optional<double> YawBiasFromFeet::Update(const Piece& piece, int64_t t_ns) {
  var_ += opt_.walk * opt_.walk * (t_ns - var_t_ns_) * 1e-9;
  var_t_ns_ = t_ns;
  if (piece.slope * piece.slope > opt_.gate_chi2 * (var_ + piece.variance)) {
    ++rejected_;
    return std::nullopt;
  }
  const double gain = var_ / (var_ + piece.variance);
  const double correction = gain * piece.slope;
  var_ *= 1 - gain;
  total_ += correction;
  ++pieces_;
  return correction;
}

std::optional<double> YawBiasFromFeet::Add(int64_t t_ns, const std::array<bool, kNumLegs>& holds,
                                           const std::array<Eigen::Vector3d, kNumLegs>& contact_w,
                                           double yaw_rate) {
  if (!enabled()) return std::nullopt;
  std::optional<Piece> best;  // of the pieces ending at this reading
  auto end_piece = [&](Pair* p) {
    const std::optional<Piece> piece = Finish(p, t_ns);
    if (piece && (!best || piece->variance < best->variance)) best = piece;
  };
  int k = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    for (int j = i + 1; j < kNumLegs; ++j, ++k) {
      Pair& p = pairs_[k];
      const Eigen::Vector2d d = (contact_w[i] - contact_w[j]).head<2>();
      if (!holds[i] || !holds[j] || d.norm() < kMinPairLength_m) {
        if (p.active) end_piece(&p);
        continue;
      }
      if (p.active && (t_ns - p.t0_ns) * 1e-9 >= opt_.max_s) end_piece(&p);
      if (!p.active) {
        p = Pair{};
        p.active = true;
        p.t0_ns = t_ns;
        p.d0 = d;
      }
      // Heading relative to the start, less the turns made from elsewhere.
      const double heading = std::atan2(p.d0.x() * d.y() - p.d0.y() * d.x(), p.d0.dot(d)) - p.turned;
      const double t = (t_ns - p.t0_ns) * 1e-9;
      ++p.n;
      p.length += (d.norm() - p.length) / p.n;
      p.st += t;
      p.sy += heading;
      p.stt += t * t;
      p.sty += t * heading;
      p.rate_sum += yaw_rate;
    }
  }
  if (!best) return std::nullopt;
  const std::optional<double> correction = Update(*best, t_ns);
  if (correction) {
    // The other pairs' headings were measured with the old bias: start them again.
    for (Pair& p : pairs_) p.active = false;
  }
  return correction;
}

}  // namespace viqu::lo

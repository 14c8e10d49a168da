#pragma once
// The gyro bias about the vertical, from pairs of stance feet. Gravity observes roll and pitch but
// not yaw, so the attitude filter's yaw drifts at the gyro's bias rate. Two feet that both hold
// keep the horizontal vector between their contact points fixed in the world; seen through the
// filter's orientation, that vector turns at exactly the rate the uncorrected bias turns the yaw.
// For each pair of feet standing together, the vector's heading over time (rotated by the
// filter's orientation, the feet's rolling taken out) is fitted with a line; its slope, at the end
// of the pair's stance, measures the remaining bias, and a scalar Kalman filter (a random-walk bias
// with a prior) weighs it by the fit's variance; a slope too far from the estimate for that
// variance (a foot that slid unflagged) is dropped. Pieces that end at the same reading (the six
// pairs of a standing robot) share feet and their creep, so only the best of them (the smallest
// variance) is used, once. Pure arithmetic on the inputs; LegOdometry says
// which feet hold and applies the result to the attitude filter.
#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "slam/measurements/joint_state.h"

namespace viqu::lo {

struct YawBiasOptions {
  double initial_std = 0.002;  // prior std of the bias about the vertical (rad/s); 0 = off
  double walk = 0.0001;        // its random walk (rad/s/sqrt(s))
  double pair_noise_m = 0.0003;  // noise of one reading of the horizontal vector between two feet (m)
  double min_s = 0.1;          // a pair standing together for less is not used (s)
  double max_s = 1.0;          // a longer one is cut into pieces this long (s)
  double max_rate = 0.02;      // a piece turning faster than this on average is not used (rad/s)
  double gate_chi2 = 9;        // a piece further from the estimate than this is dropped (chi-square, 1 dof)
};

class YawBiasFromFeet {
 public:
  explicit YawBiasFromFeet(const YawBiasOptions& opt) : opt_(opt) {}

  // Starts with no pair and the prior's variance at t_ns.
  void Reset(int64_t t_ns);

  // One encoder reading at t_ns: holds[i] says foot i is in contact, settled and not slipping;
  // contact_w[i] is its contact point relative to the body in the world frame of the filter's
  // orientation (m); yaw_rate the trunk's turn rate about the vertical (rad/s): while the robot
  // turns, its stance feet twist on the ground (by about 6% of the turn rate, against it, on
  // this floor), so pieces that turn are not used. Returns the correction to add to the bias
  // estimate about the world's vertical (rad/s) when a piece ended with this reading and moved it.
  std::optional<double> Add(int64_t t_ns, const std::array<bool, kNumLegs>& holds,
                            const std::array<Eigen::Vector3d, kNumLegs>& contact_w, double yaw_rate = 0);

  // The filter's orientation was turned by dyaw (rad) about the vertical from elsewhere (a
  // correction from vision): the headings measured so far turn with it.
  void TurnedBy(double dyaw);

  bool enabled() const { return opt_.initial_std > 0; }
  double variance() const { return var_; }       // of the bias estimate ((rad/s)^2)
  double total() const { return total_; }         // corrections added so far (rad/s)
  int pieces() const { return pieces_; }          // pair pieces used so far
  int rejected() const { return rejected_; }      // pieces dropped by the gate
  int turning() const { return turning_; }        // pieces not used because the robot turned

 private:
  struct Pair {
    bool active = false;
    int64_t t0_ns = 0;
    Eigen::Vector2d d0 = Eigen::Vector2d::Zero();  // horizontal vector at the start (m)
    double turned = 0;                            // turns from elsewhere since the start (rad)
    double length = 0;                            // mean horizontal length so far (m), for the noise
    double st = 0, sy = 0, stt = 0, sty = 0;      // sums of the line fit (s, rad)
    double rate_sum = 0;                          // of the turn rates (rad/s)
    int n = 0;
  };
  static constexpr int kPairs = kNumLegs * (kNumLegs - 1) / 2;

  // The line fit of a piece that counts: its slope (rad/s) and the slope's variance.
  struct Piece {
    double slope = 0, variance = 0;
  };
  // Ends pair p's piece at t_ns; its fit if it lasted and did not turn.
  std::optional<Piece> Finish(Pair* p, int64_t t_ns);
  // The scalar filter's update at t_ns with one piece; the correction unless the gate drops it.
  std::optional<double> Update(const Piece& piece, int64_t t_ns);

  YawBiasOptions opt_;
  std::array<Pair, kPairs> pairs_{};
  double var_ = 0;
  int64_t var_t_ns_ = 0;
  double total_ = 0;
  int pieces_ = 0;
  int rejected_ = 0;
  int turning_ = 0;
};

}  // namespace viqu::lo

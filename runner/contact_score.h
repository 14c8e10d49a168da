#pragma once
// How well the estimator's contact and foot forces follow the simulator's (issue 55 item 6;
// metrics only): per encoder sample and foot, whether its contact agrees with the debounced true
// contact (runner/foot_truth.h); each true touch-down and lift-off against the estimator's
// nearest of the same foot and kind; the estimated normal force against the simulator's while
// the foot is truly in contact. contact.csv lists the transitions.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "runner/foot_truth.h"
#include "slam/measurements/joint_state.h"

namespace viqu::runner {

// A true transition is paired with the estimator's nearest of the same foot and kind within this
// (s): under half the shortest swing of the shipped gaits (133 ms at 3 Hz and duty 0.6), so that
// a pairing never reaches the next stance. A definition of the score, not a tuning.
constexpr double kTransitionMatchS = 0.06;

struct ContactScore {
  long samples = 0;                 // foot-samples scored
  double accuracy = std::numeric_limits<double>::quiet_NaN();
  int touchdowns = 0, touchdowns_paired = 0, liftoffs = 0, liftoffs_paired = 0;
  double touchdown_err_ms_median = std::numeric_limits<double>::quiet_NaN();  // |estimated - true|, paired ones
  double liftoff_err_ms_median = std::numeric_limits<double>::quiet_NaN();
  long force_samples = 0;           // foot-samples truly in contact with a force estimate
  double normal_rmse_n = std::numeric_limits<double>::quiet_NaN();
  double true_normal_mean_n = std::numeric_limits<double>::quiet_NaN();  // mean true normal force over them
};

class ContactScorer {
 public:
  // One encoder sample: the estimator's contact and the true (debounced) contact.
  void Add(int64_t t_ns, const std::array<bool, kNumLegs>& estimated, const std::array<bool, kNumLegs>& truth);
  // One foot-force estimate (NaN where there is none) with the truth at its instant: the true
  // contact and the simulator's normal force. Scored where the foot is truly in contact.
  void AddForce(const std::array<double, kNumLegs>& est_normal_n, const std::array<bool, kNumLegs>& truth,
                const std::array<double, kNumLegs>& true_normal_n);

  // Scores against the true stances (FootTruth::Finish): those the run began or ended in have no
  // true touch-down or lift-off there. `csv` gets contact.csv.
  ContactScore Finish(const std::vector<TrueStance>& stances, std::string* csv);

 private:
  struct Transition {
    int leg;
    bool touchdown;
    int64_t t_ns;
  };
  std::vector<Transition> estimated_;
  std::array<bool, kNumLegs> last_{};
  bool have_last_ = false;
  long samples_ = 0, agree_ = 0;
  long force_samples_ = 0;
  double force_sq_ = 0, force_sum_ = 0;
};

}  // namespace viqu::runner

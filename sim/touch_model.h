#pragma once
// Foot touch sensors: the normal force on each foot plus white noise, against a threshold. Pure
// C++ on plain inputs (no MuJoCo); the simulator feeds it World::FootNormalForces().
#include <array>
#include <cstdint>
#include <random>

#include "scenario/scenario.h"
#include "slam/measurements/contact_reading.h"

namespace viqu::sim {

class TouchModel {
 public:
  TouchModel(const viqu::TouchConfig& config, uint64_t seed) : config_(config), rng_(seed) {}

  // stance[i] = force_n[i] + N(0, noise_n^2) > threshold_n. Throws viqu::InputError for a
  // non-finite force.
  viqu::ContactReading Measure(int64_t t_ns, const std::array<double, viqu::kNumLegs>& force_n);

 private:
  viqu::TouchConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace viqu::sim

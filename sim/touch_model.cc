#include "sim/touch_model.h"

#include <cmath>

#include "common/errors.h"

namespace viqu::sim {

viqu::ContactReading TouchModel::Measure(int64_t t_ns, const std::array<double, viqu::kNumLegs>& force_n) {
  viqu::ContactReading r;
  r.t_ns = t_ns;
  for (int i = 0; i < viqu::kNumLegs; ++i) {
    if (!std::isfinite(force_n[i])) throw InputError("touch sensor: non-finite foot force");
    r.stance[i] = force_n[i] + config_.noise_n * normal_(rng_) > config_.threshold_n;
  }
  return r;
}

}  // namespace viqu::sim

#include "sim/camera_noise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

#include "common/errors.h"

namespace viqu::sim {
namespace {

// The rounded Gaussian round(N(0, std^2)) as a discrete distribution sampled by inversion of a
// 32-bit uniform: value[i] is taken when upper[i-1] <= u < upper[i] (upper[] holds the CDF times
// 2^32). Values whose probability is below 2^-33 fall outside the table (beyond about 6.3 std),
// which is the resolution of a 32-bit draw anyway. guide[j] is the index of the interval that
// holds u = j * 2^20, so a draw starts at guide[u >> 20] and steps on only in the few cells that
// an interval boundary crosses (a branch that is rarely taken); 4096 cells keep the guide in the
// first-level cache (2^16 cells ran 10% slower).
struct RoundedGaussianTable {
  double noise_std = -1;
  std::vector<int16_t> value;
  std::vector<uint64_t> upper;
  std::vector<uint16_t> guide;  // 2^12 cells
};

double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

void Build(double noise_std, RoundedGaussianTable* t) {
  t->noise_std = noise_std;
  t->value.clear();
  t->upper.clear();
  // Grey levels beyond 255 cannot change a saturated 8-bit sum, so the support stops there.
  const int k_max = static_cast<int>(std::min(255.0, std::ceil(7.0 * noise_std) + 1));
  const double two32 = 4294967296.0;
  for (int k = -k_max; k <= k_max; ++k) {
    const double cdf = (k == k_max) ? 1.0 : Phi((k + 0.5) / noise_std);
    const uint64_t upper = static_cast<uint64_t>(std::llround(cdf * two32));
    if (!t->upper.empty() && upper == t->upper.back()) continue;  // probability below 2^-33
    if (upper == 0) continue;
    t->value.push_back(static_cast<int16_t>(k));
    t->upper.push_back(upper);
  }
  t->upper.back() = uint64_t{1} << 32;  // every draw lands in the table
  t->guide.resize(size_t{1} << 12);
  size_t i = 0;
  for (size_t j = 0; j < t->guide.size(); ++j) {
    const uint64_t u = static_cast<uint64_t>(j) << 20;
    while (t->upper[i] <= u) ++i;
    t->guide[j] = static_cast<uint16_t>(i);
  }
}

// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", 2014):
// a 64-bit counter passed through a mixing function; each output gives two 32-bit draws.
struct SplitMix64 {
  uint64_t state;
  uint64_t Next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
};

// The table's arrays as plain pointers: the image's bytes may alias anything, so the loop must
// not read the vectors' data pointers through the table (they would be reloaded every store).
struct TableView {
  const uint16_t* guide;
  const uint64_t* upper;
  const int16_t* value;
  int Draw(uint32_t u) const {
    size_t i = guide[u >> 20];
    while (u >= upper[i]) ++i;
    return value[i];
  }
};

inline uint8_t Saturate(int v) { return static_cast<uint8_t>(v < 0 ? 0 : (v > 255 ? 255 : v)); }

}  // namespace

void AddPixelNoise(cv::Mat* rgb, double noise_std, std::mt19937_64* rng) {
  if (rgb == nullptr || rng == nullptr) {
    throw viqu::InputError("AddPixelNoise: null image or generator");
  }
  if (!(noise_std >= 0.0) || !std::isfinite(noise_std)) {
    std::ostringstream msg;
    msg << "AddPixelNoise: noise_std must be finite and >= 0, got " << noise_std;
    throw viqu::InputError(msg.str());
  }
  if (rgb->empty() || noise_std == 0.0) return;
  if (rgb->depth() != CV_8U) {
    std::ostringstream msg;
    msg << "AddPixelNoise: expected an 8-bit image, got OpenCV type " << rgb->type();
    throw viqu::InputError(msg.str());
  }
  // The table depends only on the std: kept per thread for the last std used (a run has one).
  thread_local RoundedGaussianTable table;
  if (table.noise_std != noise_std) Build(noise_std, &table);

  const TableView t{table.guide.data(), table.upper.data(), table.value.data()};
  SplitMix64 gen{(*rng)()};
  const size_t row_values = static_cast<size_t>(rgb->cols) * static_cast<size_t>(rgb->channels());
  for (int r = 0; r < rgb->rows; ++r) {
    uint8_t* p = rgb->ptr<uint8_t>(r);
    size_t i = 0;
    for (; i + 1 < row_values; i += 2) {
      const uint64_t bits = gen.Next();
      p[i] = Saturate(p[i] + t.Draw(static_cast<uint32_t>(bits)));
      p[i + 1] = Saturate(p[i + 1] + t.Draw(static_cast<uint32_t>(bits >> 32)));
    }
    if (i < row_values) p[i] = Saturate(p[i] + t.Draw(static_cast<uint32_t>(gen.Next())));
  }
}

}  // namespace viqu::sim

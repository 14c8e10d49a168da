// The descriptor distance (slam/features/hamming.h) against a bit-by-bit count.
#include <random>

#include <gtest/gtest.h>

#include "slam/features/hamming.h"

namespace viqu::slam {
namespace {

int NaiveBits(const uint8_t* a, const uint8_t* b, int n) {
  int d = 0;
  for (int i = 0; i < n; ++i) {
    for (int bit = 0; bit < 8; ++bit) d += ((a[i] ^ b[i]) >> bit) & 1;
  }
  return d;
}

TEST(Hamming, EqualsABitByBitCount) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int n : {1, 7, 8, 13, 32, 61}) {
    for (int trial = 0; trial < 200; ++trial) {
      uint8_t a[64], b[64];
      for (int i = 0; i < n; ++i) {
        a[i] = static_cast<uint8_t>(byte(rng));
        b[i] = static_cast<uint8_t>(byte(rng));
      }
      EXPECT_EQ(HammingDistance(a, b, n), NaiveBits(a, b, n)) << n;
    }
  }
  EXPECT_EQ(PopCount64(~0ULL), 64);
  EXPECT_EQ(PopCount64(0), 0);
  EXPECT_EQ(PopCount64(0x8000000000000001ULL), 2);
}

}  // namespace
}  // namespace viqu::slam

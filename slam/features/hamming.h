#pragma once
// Hamming distance of binary descriptors. The bit count is written out (SWAR) rather than
// __builtin_popcountll: without -mpopcnt (not in the x86-64 baseline that Debian builds for)
// the builtin becomes a call into libgcc, which showed up in the tracking profile.
#include <cstdint>
#include <cstring>

namespace viqu::slam {

inline int PopCount64(uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

// Differing bits of two descriptors of `bytes` bytes.
inline int HammingDistance(const uint8_t* a, const uint8_t* b, int bytes) {
  int d = 0, k = 0;
  for (; k + 8 <= bytes; k += 8) {
    uint64_t x, y;
    std::memcpy(&x, a + k, 8);
    std::memcpy(&y, b + k, 8);
    d += PopCount64(x ^ y);
  }
  for (; k < bytes; ++k) d += PopCount64(static_cast<uint64_t>(a[k] ^ b[k]));
  return d;
}

}  // namespace viqu::slam

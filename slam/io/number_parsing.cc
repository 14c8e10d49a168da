#include "slam/io/number_parsing.h"

#include <charconv>
#include <cmath>

namespace viqu::io {

bool ParseInt64(const std::string& text, int64_t* out) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, *out);
  return r.ec == std::errc() && r.ptr == end;
}

bool ParseSecondsAsNs(const std::string& text, int64_t* out_ns) {
  size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (negative) ++i;
  const size_t int_begin = i;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
  const size_t int_end = i;
  size_t frac_begin = i, frac_end = i;
  if (i < text.size() && text[i] == '.') {
    frac_begin = ++i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    frac_end = i;
  }
  if (i != text.size() || (int_end == int_begin && frac_end == frac_begin)) return false;

  int64_t seconds = 0;
  if (int_end > int_begin) {
    const auto r = std::from_chars(text.data() + int_begin, text.data() + int_end, seconds);
    if (r.ec != std::errc()) return false;
  }
  // Fraction: the first 9 digits are nanoseconds, the 10th rounds.
  int64_t frac_ns = 0;
  for (size_t k = 0; k < 9; ++k) {
    const size_t pos = frac_begin + k;
    frac_ns = frac_ns * 10 + (pos < frac_end ? text[pos] - '0' : 0);
  }
  if (frac_end > frac_begin + 9 && text[frac_begin + 9] >= '5') ++frac_ns;
  int64_t ns = 0;
  if (__builtin_mul_overflow(seconds, int64_t{1000000000}, &ns)) return false;
  if (__builtin_add_overflow(ns, frac_ns, &ns)) return false;
  *out_ns = negative ? -ns : ns;
  return true;
}

bool ParseFiniteDouble(const std::string& text, double* out) {
  if (text.empty()) return false;
  const char* begin = text.data();
  if (*begin == '+') ++begin;  // from_chars takes no '+'
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(begin, end, *out);
  return r.ec == std::errc() && r.ptr == end && std::isfinite(*out);
}

}  // namespace viqu::io

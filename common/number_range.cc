#include "common/number_range.h"

#include <cmath>
#include <cstdio>

namespace viqu {
namespace {

std::string FormatBound(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

}  // namespace

bool NumberRange::Contains(double v) const {
  if (std::isnan(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string NumberRange::Describe(const std::string& noun) const {
  const bool has_lo = std::isfinite(lo);
  const bool has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    return noun + " in " + (lo_open ? "(" : "[") + FormatBound(lo) + ", " + FormatBound(hi) +
           (hi_open ? ")" : "]");
  }
  if (has_lo) return noun + (lo_open ? " > " : " >= ") + FormatBound(lo);
  if (has_hi) return noun + (hi_open ? " < " : " <= ") + FormatBound(hi);
  return noun;
}

}  // namespace viqu

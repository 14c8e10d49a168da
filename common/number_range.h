#pragma once
#include <limits>
#include <string>

namespace viqu {

// An interval of accepted numbers, with its description for messages ("a number in (0, 1)").
struct NumberRange {
  double lo = -std::numeric_limits<double>::infinity();  // lower bound
  double hi = std::numeric_limits<double>::infinity();   // upper bound
  bool lo_open = false;                                  // lower bound excluded
  bool hi_open = false;                                  // upper bound excluded

  static NumberRange Any() { return {}; }
  static NumberRange Positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static NumberRange NonNegative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static NumberRange Open(double a, double b) { return {a, b, true, true}; }
  static NumberRange Closed(double a, double b) { return {a, b, false, false}; }
  static NumberRange AtLeast(double a) { return {a, std::numeric_limits<double>::infinity(), false, false}; }
  static NumberRange ClosedOpen(double a, double b) { return {a, b, false, true}; }
  static NumberRange OpenClosed(double a, double b) { return {a, b, true, false}; }

  bool Contains(double v) const;
  // "a number in (0, 1)", "an integer >= 0", ... with `noun` = "a number" or "an integer".
  std::string Describe(const std::string& noun) const;
};

}  // namespace viqu

#include "slam/io/calibration_check.h"

#include <cmath>
#include <cstdio>

#include "common/errors.h"

namespace viqu::io {
namespace {

std::string Num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

std::string Key(const std::string& where, const std::string& fallback) { return where.empty() ? fallback : where; }

// The field of view (deg) that focal length f (px) gives across `size` px.
double FovDeg(double f, int size) { return 2.0 * std::atan2(0.5 * size, f) * 180.0 / M_PI; }

}  // namespace

std::string CalibrationProblem(const CameraCalibration& c, const CalibrationKeys& keys, const std::string& source) {
  const PinholeIntrinsics& k = c.pinhole;
  const std::string image = std::to_string(k.width) + "x" + std::to_string(k.height) + " image";
  const auto focal = [&](const std::string& key, const char* name, double f, int size, const char* across) -> std::string {
    const double fov = std::isfinite(f) && f > 0 ? FovDeg(f, size) : 0;
    if (std::isfinite(f) && f > 0 && fov >= kMinFovDeg && fov <= kMaxFovDeg) return "";
    return Key(key, source) + ": " + name + " " + Num(f) + " px is no focal length of a camera for a " + image +
           ": the field of view across its " + across + " must lie in [" + Num(kMinFovDeg) + ", " + Num(kMaxFovDeg) +
           "] deg, i.e. " + name + " in [" + Num(0.5 * size / std::tan(0.5 * kMaxFovDeg * M_PI / 180)) + ", " +
           Num(0.5 * size / std::tan(0.5 * kMinFovDeg * M_PI / 180)) + "] px";
  };
  std::string p = focal(keys.fx, "fx", k.fx, k.width, "width");
  if (p.empty()) p = focal(keys.fy, "fy", k.fy, k.height, "height");
  if (!p.empty()) return p;
  const auto centre = [&](const std::string& key, const char* name, double x, int size) -> std::string {
    if (std::isfinite(x) && x >= 0 && x <= size) return "";
    return Key(key, source) + ": " + name + " " + Num(x) + " px is outside the " + image +
           ": the principal point lies in the image (" + name + " in [0, " + std::to_string(size) + "])";
  };
  p = centre(keys.cx, "cx", k.cx, k.width);
  if (p.empty()) p = centre(keys.cy, "cy", k.cy, k.height);
  if (!p.empty()) return p;

  if (c.distortion.empty()) return "";
  const std::string where = Key(keys.distortion, source);
  for (double d : c.distortion) {
    if (!std::isfinite(d)) return where + ": a distortion coefficient is not a finite number";
  }
  const double k1 = c.distortion[0], k2 = c.distortion.size() > 1 ? c.distortion[1] : 0;
  const double p1 = c.distortion.size() > 2 ? c.distortion[2] : 0, p2 = c.distortion.size() > 3 ? c.distortion[3] : 0;
  const double k3 = c.distortion.size() > 4 ? c.distortion[4] : 0;
  if (std::abs(p1) > kMaxTangential || std::abs(p2) > kMaxTangential) {
    return where + ": tangential distortion p1 " + Num(p1) + ", p2 " + Num(p2) + ": beyond +-" + Num(kMaxTangential) +
           " (real lenses are of order 1e-3)";
  }
  // The image corner farthest from the principal point, in normalised coordinates.
  const double u = std::max(k.cx, k.width - k.cx) / k.fx, v = std::max(k.cy, k.height - k.cy) / k.fy;
  const double r_max = std::hypot(u, v);
  constexpr int kSteps = 200;  // radii checked out to the corner
  for (int i = 1; i <= kSteps; ++i) {
    const double r = r_max * i / kSteps, r2 = r * r;
    const double factor = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double slope = 1 + r2 * (3 * k1 + r2 * (5 * k2 + r2 * 7 * k3));  // d(r * factor)/dr
    if (!(factor >= kMinRadialFactor && factor <= kMaxRadialFactor)) {
      return where + ": radial distortion k1 " + Num(k1) + ", k2 " + Num(k2) + ", k3 " + Num(k3) + " scales radii by " +
             Num(factor) + " at " + Num(r) + " (normalised; the image corner is at " + Num(r_max) + "): outside [" +
             Num(kMinRadialFactor) + ", " + Num(kMaxRadialFactor) + "]";
    }
    if (slope <= 0) {
      return where + ": radial distortion k1 " + Num(k1) + ", k2 " + Num(k2) + ", k3 " + Num(k3) +
             " folds the image: the distorted radius stops growing at " + Num(r) + " (normalised; the image corner is at " +
             Num(r_max) + ")";
    }
  }
  return "";
}

void CheckCalibration(const CameraCalibration& c, const CalibrationKeys& keys, const std::string& source) {
  const std::string problem = CalibrationProblem(c, keys, source);
  if (!problem.empty()) throw InputError(problem);
}

}  // namespace viqu::io

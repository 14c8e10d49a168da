#pragma once
// Is a calibration one a camera can have? A calibration file with `Camera.cx: 99999` for a 640 px
// image, `Camera.fx: 1e300` or `k1: 1e6` would track nothing and give a figure (ATE 19.6 m); it is
// refused, naming the key, before any frame is read.
#include <string>

#include "slam/io/camera_calibration.h"

namespace viqu::io {

// Where each value of a calibration was written, for messages: "FILE:LINE:COL: key 'Camera.cx'"
// (empty: the calibration's source alone).
struct CalibrationKeys {
  std::string fx, fy, cx, cy, distortion;
};

// Bounds on a pinhole camera with radial-tangential distortion (every image size):
// - the field of view across the width (fx) and the height (fy) between kMinFovDeg and
//   kMaxFovDeg: a pinhole model cannot reach 180 deg, and under 1 deg is a telescope;
// - the principal point inside the image;
// - the radial factor 1 + k1 r^2 + k2 r^4 + k3 r^6 within [kMinRadialFactor, kMaxRadialFactor]
//   and the distorted radius increasing with the undistorted one, for every radius out to the
//   image's corner (else the undistortion folds the image onto itself);
// - the tangential coefficients p1, p2 at most kMaxTangential in magnitude.
constexpr double kMinFovDeg = 1;
constexpr double kMaxFovDeg = 179;
// Wide lenses modelled radial-tangentially reach factors of about 0.6-0.8 at the corner (EuRoC's
// 0.79, TUM freiburg1's 1.08); a factor outside [0.25, 4] shrinks or stretches the corner by more
// than any lens this model describes.
constexpr double kMinRadialFactor = 0.25;
constexpr double kMaxRadialFactor = 4.0;
// Decentring of real lenses is of order 1e-3 (EuRoC 1.8e-4 to 2e-5, TUM 5e-3); 0.1 shifts the
// corner by a fifth of its radius.
constexpr double kMaxTangential = 0.1;

// "" when `c` (its image size known: width, height > 0) is within the bounds above; else the
// problem, starting with the key it is about (from `keys`, else `source`): "FILE:3:5: key
// 'Camera.cx' is 99999, outside the 640x480 image: ...".
std::string CalibrationProblem(const CameraCalibration& c, const CalibrationKeys& keys, const std::string& source);

// Throws InputError(CalibrationProblem(...)) when there is a problem.
void CheckCalibration(const CameraCalibration& c, const CalibrationKeys& keys, const std::string& source);

}  // namespace viqu::io

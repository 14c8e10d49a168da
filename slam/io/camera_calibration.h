#pragma once
#include <vector>

#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// A raw (unrectified) pinhole camera with radial-tangential distortion.
struct CameraCalibration {
  PinholeIntrinsics pinhole;        // K and the image size of the raw images (px)
  std::vector<double> distortion;   // k1, k2, p1, p2[, k3] (OpenCV order); empty = none
};

// True when the distortion coefficients are all zero (or absent).
inline bool HasNoDistortion(const CameraCalibration& c) {
  for (double d : c.distortion) {
    if (d != 0) return false;
  }
  return true;
}

}  // namespace viqu::io

#pragma once
#include <string>

#include "slam/io/camera_calibration.h"

namespace viqu::io {

// The camera of a TUM RGB-D sequence.
struct TumCamera {
  CameraCalibration calibration;  // intrinsics and size; distortion (freiburg1/2 are distorted)
  double depth_scale = 5000;      // depth PNG value per metre
  std::string source;             // where the values came from, for messages
};

// The camera of the sequence in `dir`:
// 1. `viqu_intrinsics.yaml`, else `camera.yaml` in `dir` (written by sim/tum_recorder): keys
//    fx, fy, cx, cy, width, height (required), depth_scale (default 5000) and distortion
//    [k1, k2, p1, p2(, k3)] (default none); any other key is an error (FILE:LINE:COL);
// 2. else TUM's published calibration of the sensor named in the folder name ("freiburg1",
//    "freiburg2", "freiburg3"; 640x480, with the distortion of freiburg1/2);
// 3. else the freiburg3 values (fx 535.4, fy 539.2, cx 320.1, cy 247.6, no distortion).
TumCamera ReadTumCamera(const std::string& dir);

}  // namespace viqu::io

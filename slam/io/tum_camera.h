#pragma once
#include <string>

#include "slam/io/calibration_check.h"
#include "slam/io/camera_calibration.h"

namespace viqu::io {

// The camera of a TUM RGB-D sequence.
struct TumCamera {
  CameraCalibration calibration;  // intrinsics and size; distortion (freiburg1/2 are distorted)
  double depth_scale = 5000;      // depth PNG value per metre
  std::string source;             // where the values came from, for messages
  CalibrationKeys keys;           // where each value was written (a file's), for messages
};

// The camera of the sequence in `dir`:
// 1. `viqu_intrinsics.yaml`, else `camera.yaml` in `dir` (written by sim/tum_recorder; any
//    format ReadCameraFile reads, camera_file.h);
// 2. else TUM's published calibration of the sensor named in the folder name ("freiburg1",
//    "freiburg2", "freiburg3"; 640x480, with the distortion of freiburg1/2);
// 3. else InputError naming the folder and --camera: no calibration is guessed.
TumCamera ReadTumCamera(const std::string& dir);

}  // namespace viqu::io

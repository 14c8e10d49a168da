#pragma once
// A camera calibration file given on the command line (`viqu slam --camera FILE`).
#include <string>

#include "slam/io/tum_camera.h"

namespace viqu::io {

// Reads one of:
// - viqu's camera.yaml (what sim/tum_recorder writes): fx, fy, cx, cy, width, height required,
//   depth_scale, distortion [k1, k2, p1, p2(, k3)] optional; any other key is an error;
// - an ORB-SLAM2 settings file (`%YAML:1.0`; Camera.fx, .fy, .cx, .cy, .k1, .k2, .p1, .p2, .k3,
//   Camera.width / Camera.height, DepthMapFactor);
// - an ORB-SLAM3 settings file (Camera.type "PinHole"; Camera1.fx ... Camera1.k3,
//   Camera.width / Camera.height, RGBD.DepthMapFactor).
// ORB-SLAM files hold many settings of ORB-SLAM's own: those are ignored. Where width and
// height are missing (older ORB-SLAM2 files) they are 0: the reader takes the images' size.
// Errors name FILE:LINE:COL (InputError).
TumCamera ReadCameraFile(const std::string& path);

}  // namespace viqu::io

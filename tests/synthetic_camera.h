#pragma once
// The camera of the optimisers' synthetic tests: 640x480, f 400 px, principal point at the
// centre, a 4 cm baseline.
#include "slam/core/camera.h"

namespace viqu::testing {

inline slam::StereoCamera SyntheticStereoCamera() {
  slam::StereoCamera c;
  c.width = 640;
  c.height = 480;
  c.fx = c.fy = 400;
  c.cx = 319.5;
  c.cy = 239.5;
  c.bf = 400 * 0.04;
  return c;
}

}  // namespace viqu::testing

#include "slam/io/tum_camera.h"

#include <filesystem>

#include "common/errors.h"
#include "slam/io/camera_file.h"

namespace viqu::io {
namespace {

namespace fs = std::filesystem;

// TUM RGB-D "ROS default" calibrations of the colour cameras (vision.in.tum.de file formats page).
TumCamera Freiburg(int which) {
  TumCamera c;
  PinholeIntrinsics& k = c.calibration.pinhole;
  k.width = 640;
  k.height = 480;
  switch (which) {
    case 1:
      k.fx = 517.3;
      k.fy = 516.5;
      k.cx = 318.6;
      k.cy = 255.3;
      c.calibration.distortion = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
      break;
    case 2:
      k.fx = 520.9;
      k.fy = 521.0;
      k.cx = 325.1;
      k.cy = 249.7;
      c.calibration.distortion = {0.2312, -0.7849, -0.0033, -0.0001, 0.9172};
      break;
    default:  // freiburg3: the images are undistorted already
      k.fx = 535.4;
      k.fy = 539.2;
      k.cx = 320.1;
      k.cy = 247.6;
      break;
  }
  return c;
}

}  // namespace

TumCamera ReadTumCamera(const std::string& dir) {
  std::error_code ec;
  for (const char* name : {"viqu_intrinsics.yaml", "camera.yaml"}) {
    const fs::path p = fs::path(dir) / name;
    if (fs::exists(p, ec)) return ReadCameraFile(p.string());
  }
  fs::path d = fs::absolute(dir, ec).lexically_normal();
  if (d.filename().empty()) d = d.parent_path();
  const std::string folder = d.filename().string();
  for (int which : {1, 2, 3}) {
    if (folder.find("freiburg" + std::to_string(which)) != std::string::npos) {
      TumCamera c = Freiburg(which);
      c.source = "TUM freiburg" + std::to_string(which) + " calibration (from the folder name)";
      return c;
    }
  }
  // No silent guess: a sequence of another camera tracked with a freiburg calibration gives
  // wrong figures with exit 0.
  throw InputError(dir + ": no camera calibration: the folder has no camera.yaml and its name says no freiburg1, "
                   "freiburg2 or freiburg3; pass --camera FILE (viqu's camera.yaml or an ORB-SLAM2/ORB-SLAM3 settings file)");
}

}  // namespace viqu::io

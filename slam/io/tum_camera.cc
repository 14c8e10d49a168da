#include "slam/io/tum_camera.h"

#include <filesystem>

#include "common/yaml_map_reader.h"
#include "common/yaml_strict.h"

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

TumCamera ReadYaml(const std::string& path) {
  const YamlSource src(path);
  YamlMapReader top(src, LoadYamlFile(path), "");
  TumCamera c;
  c.source = path;
  PinholeIntrinsics& k = c.calibration.pinhole;
  for (const char* key : {"fx", "fy", "cx", "cy", "width", "height"}) top.Require(key);
  top.Number("fx", &k.fx, NumberRange::Positive());
  top.Number("fy", &k.fy, NumberRange::Positive());
  top.Number("cx", &k.cx);
  top.Number("cy", &k.cy);
  top.Integer("width", &k.width, NumberRange::Closed(1, 100000));
  top.Integer("height", &k.height, NumberRange::Closed(1, 100000));
  top.Number("depth_scale", &c.depth_scale, NumberRange::Positive());
  top.NumberList("distortion", &c.calibration.distortion, 0, NumberRange::Any(), 4);
  if (c.calibration.distortion.size() > 5) {
    src.Fail("distortion", top.Get("distortion"), "expected 4 or 5 coefficients [k1, k2, p1, p2(, k3)]");
  }
  top.RejectUnknownKeys();
  return c;
}

}  // namespace

TumCamera ReadTumCamera(const std::string& dir) {
  std::error_code ec;
  for (const char* name : {"viqu_intrinsics.yaml", "camera.yaml"}) {
    const fs::path p = fs::path(dir) / name;
    if (fs::exists(p, ec)) return ReadYaml(p.string());
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
  TumCamera c = Freiburg(3);
  c.source = "TUM freiburg3 calibration (default: no camera.yaml, no freiburgN in the folder name)";
  return c;
}

}  // namespace viqu::io

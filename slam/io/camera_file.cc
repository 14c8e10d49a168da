#include "slam/io/camera_file.h"

#include "common/errors.h"
#include "common/yaml_map_reader.h"
#include "common/yaml_strict.h"
#include "slam/io/euroc_sensor_yaml.h"

namespace viqu::io {
namespace {

// "FILE:LINE:COL: key 'NAME'" of a key that `top` read, or "" when the file does not have it.
std::string KeyWhere(const YamlSource& src, YamlMapReader& top, const std::string& key) {
  if (key.empty()) return "";
  const YAML::Node node = top.Get(key);
  return node.IsDefined() ? src.Where(key, node) + ": key '" + key + "'" : "";
}

void NoteKeys(const YamlSource& src, YamlMapReader& top, const std::string& prefix, const std::string& distortion_key,
              CalibrationKeys* keys) {
  keys->fx = KeyWhere(src, top, prefix + "fx");
  keys->fy = KeyWhere(src, top, prefix + "fy");
  keys->cx = KeyWhere(src, top, prefix + "cx");
  keys->cy = KeyWhere(src, top, prefix + "cy");
  keys->distortion = KeyWhere(src, top, distortion_key);
}

TumCamera ReadViqu(const YamlSource& src, const YAML::Node& root, const std::string& path) {
  YamlMapReader top(src, root, "");
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
  NoteKeys(src, top, "", "distortion", &c.keys);
  CheckCalibration(c.calibration, c.keys, path);
  return c;
}

// ORB-SLAM2 (`prefix` "Camera.") or ORB-SLAM3 (`prefix` "Camera1.") settings.
TumCamera ReadOrbSlam(const YamlSource& src, const YAML::Node& root, const std::string& path, const std::string& prefix) {
  YamlMapReader top(src, root, "");
  TumCamera c;
  PinholeIntrinsics& k = c.calibration.pinhole;
  if (top.Has("Camera.type")) {
    std::string type;
    top.String("Camera.type", &type);
    if (type != "PinHole") {
      src.Fail("Camera.type", top.Get("Camera.type"), "camera type '" + type + "': only PinHole calibrations are read");
    }
  }
  for (const char* key : {"fx", "fy", "cx", "cy"}) top.Require(prefix + key);
  top.Number(prefix + "fx", &k.fx, NumberRange::Positive());
  top.Number(prefix + "fy", &k.fy, NumberRange::Positive());
  top.Number(prefix + "cx", &k.cx);
  top.Number(prefix + "cy", &k.cy);
  k.width = k.height = 0;  // the images' size unless given
  top.Integer("Camera.width", &k.width, NumberRange::Closed(1, 100000));
  top.Integer("Camera.height", &k.height, NumberRange::Closed(1, 100000));
  if ((k.width == 0) != (k.height == 0)) {
    src.Fail(k.width == 0 ? "Camera.height" : "Camera.width", top.Get(k.width == 0 ? "Camera.height" : "Camera.width"),
             "Camera.width and Camera.height go together");
  }
  std::vector<double> d(5, 0.0);
  bool any = false;
  const char* names[5] = {"k1", "k2", "p1", "p2", "k3"};
  std::string first_distortion_key;
  for (int i = 0; i < 5; ++i) {
    const bool given = top.Number(prefix + names[i], &d[i]);
    if (given && first_distortion_key.empty()) first_distortion_key = prefix + names[i];
    any = given || any;
  }
  if (any) c.calibration.distortion = d;
  for (const char* key : {"DepthMapFactor", "RGBD.DepthMapFactor"}) top.Number(key, &c.depth_scale, NumberRange::Positive());
  c.source = path + " (ORB-SLAM" + (prefix == "Camera1." ? "3" : "2") + " settings)";
  NoteKeys(src, top, prefix, first_distortion_key, &c.keys);
  // Without an image size the reader checks it once the images give the size.
  if (k.width > 0) CheckCalibration(c.calibration, c.keys, c.source);
  return c;
}

}  // namespace

TumCamera ReadCameraFile(const std::string& path) {
  // OpenCV-flavoured YAML ("%YAML:1.0", as ORB-SLAM's files and EuRoC's sensor.yaml are written).
  const YAML::Node root = LoadEurocYaml(path);
  const YamlSource src(path);
  if (!root.IsMap()) throw InputError(path + ": expected a map of calibration keys");
  if (root["Camera1.fx"]) return ReadOrbSlam(src, root, path, "Camera1.");
  // Any Camera.* key makes it an ORB-SLAM2 file: a missing Camera.fx is then named as such.
  for (const auto& kv : root) {
    if (kv.first.Scalar().rfind("Camera.", 0) == 0) return ReadOrbSlam(src, root, path, "Camera.");
  }
  return ReadViqu(src, root, path);
}

}  // namespace viqu::io

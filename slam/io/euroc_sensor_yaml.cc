#include "slam/io/euroc_sensor_yaml.h"

#include <cmath>

#include <Eigen/SVD>

#include "common/errors.h"
#include "slam/io/calibration_check.h"
#include "common/yaml_map_reader.h"
#include "common/yaml_strict.h"

namespace viqu::io {
namespace {

Eigen::Isometry3d ReadTransform(const YamlSource& src, YamlMapReader* top) {
  top->Require("T_BS");
  YamlMapReader t = top->Map("T_BS");
  int rows = 4, cols = 4;
  t.Integer("rows", &rows, NumberRange::Closed(4, 4));
  t.Integer("cols", &cols, NumberRange::Closed(4, 4));
  t.Require("data");
  std::vector<double> d;
  t.NumberList("data", &d, 16);
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = d[4 * r + c];
  }
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  const bool rigid = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-3 && R.determinant() > 0 &&
                     m.bottomRows<1>().isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-9);
  if (!rigid) src.Fail("T_BS.data", t.Get("data"), "T_BS is not a rigid transform (rotation and translation)");
  // Re-orthonormalise the rotation printed with a few digits.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = svd.matrixU() * svd.matrixV().transpose();
  T.translation() = m.topRightCorner<3, 1>();
  return T;
}

}  // namespace

YAML::Node LoadEurocYaml(const std::string& path) {
  std::string s = ReadYamlFileText(path);
  // Blank directive lines ("%YAML:1.0"), keeping the newline so that line numbers stay.
  size_t pos = 0;
  while (pos < s.size()) {
    const size_t end = s.find('\n', pos);
    const size_t len = (end == std::string::npos ? s.size() : end) - pos;
    if (len > 0 && s[pos] == '%') s.replace(pos, len, std::string(len, ' '));
    if (end == std::string::npos) break;
    pos = end + 1;
  }
  return LoadYamlText(s, path);
}

EurocCameraSensor ReadEurocCameraSensor(const std::string& path) {
  const YAML::Node root = LoadEurocYaml(path);
  const YamlSource src(path);
  YamlMapReader top(src, root, "");
  EurocCameraSensor out;
  out.T_B_S = ReadTransform(src, &top);

  std::string model = "pinhole";
  top.String("camera_model", &model);
  if (model != "pinhole") {
    src.Fail("camera_model", top.Get("camera_model"), "camera_model '" + model + "' is not supported (pinhole only)");
  }
  std::vector<double> res, k;
  top.Require("resolution");
  top.NumberList("resolution", &res, 2, NumberRange::Closed(1, 100000));
  top.Require("intrinsics");
  top.NumberList("intrinsics", &k, 4);
  if (res[0] != std::floor(res[0]) || res[1] != std::floor(res[1])) {
    src.Fail("resolution", top.Get("resolution"), "resolution must be two whole numbers [width, height]");
  }
  if (!(k[0] > 0 && k[1] > 0)) src.Fail("intrinsics", top.Get("intrinsics"), "focal lengths fu, fv must be > 0");
  PinholeIntrinsics& p = out.calibration.pinhole;
  p.width = static_cast<int>(res[0]);
  p.height = static_cast<int>(res[1]);
  p.fx = k[0];
  p.fy = k[1];
  p.cx = k[2];
  p.cy = k[3];

  std::string dist_model = "radial-tangential";
  top.String("distortion_model", &dist_model);
  if (dist_model != "radial-tangential" && dist_model != "radtan") {
    src.Fail("distortion_model", top.Get("distortion_model"),
             "distortion_model '" + dist_model + "' is not supported (radial-tangential only)");
  }
  std::vector<double> d;
  if (top.NumberList("distortion_coefficients", &d, 0, NumberRange::Any(), 4)) {
    if (d.size() > 5) {
      src.Fail("distortion_coefficients", top.Get("distortion_coefficients"),
               "expected 4 or 5 coefficients [k1, k2, p1, p2(, k3)]");
    }
  }
  out.calibration.distortion = d;
  CalibrationKeys keys;
  keys.fx = keys.fy = keys.cx = keys.cy = src.Where("intrinsics", top.Get("intrinsics")) + ": key 'intrinsics'";
  if (!d.empty()) {
    keys.distortion = src.Where("distortion_coefficients", top.Get("distortion_coefficients")) + ": key 'distortion_coefficients'";
  }
  CheckCalibration(out.calibration, keys, path);
  return out;
}

Eigen::Isometry3d ReadEurocSensorTransform(const std::string& path) {
  const YAML::Node root = LoadEurocYaml(path);
  const YamlSource src(path);
  YamlMapReader top(src, root, "");
  return ReadTransform(src, &top);
}

}  // namespace viqu::io

#pragma once
// The sensor.yaml files of the EuRoC MAV layout (also written by sim/euroc_recorder).
#include <string>

#include <Eigen/Geometry>
#include <yaml-cpp/yaml.h>

#include "slam/io/camera_calibration.h"

namespace viqu::io {

struct EurocCameraSensor {
  CameraCalibration calibration;  // intrinsics, resolution, radial-tangential distortion
  Eigen::Isometry3d T_B_S = Eigen::Isometry3d::Identity();  // camera (optical) frame in the body
};

// Parses a EuRoC sensor.yaml. The "%YAML:1.0" directive line of the original files (which
// yaml-cpp rejects) is blanked first, so that messages keep the file's line numbers. Missing
// file or syntax error: InputError "FILE[:LINE:COL]: ...".
YAML::Node LoadEurocYaml(const std::string& path);

// A camera sensor.yaml: T_BS (4x4, row-major, a rigid transform), resolution [w, h],
// intrinsics [fu, fv, cu, cv], camera_model pinhole, distortion_model radial-tangential with
// distortion_coefficients [k1, k2, p1, p2(, k3)]. Anything else: InputError with FILE:LINE:COL.
EurocCameraSensor ReadEurocCameraSensor(const std::string& path);

// T_BS of any sensor.yaml (e.g. imu0). Missing key or not a rigid transform: InputError.
Eigen::Isometry3d ReadEurocSensorTransform(const std::string& path);

}  // namespace viqu::io

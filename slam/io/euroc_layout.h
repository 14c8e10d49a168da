#pragma once
// The camera part of the EuRoC MAV layout, shared by the EuRoC reader and the reader of the
// project's own recordings (sim/euroc_recorder writes the same layout).
#include <string>
#include <vector>

#include "slam/io/euroc_sensor_yaml.h"
#include "slam/io/image_list.h"

namespace viqu::io {

// The mav0 folder of a dataset: `dir` itself when it is named mav0 or holds cam0/data.csv,
// else dir/mav0. Missing folder: InputError naming it.
std::string FindMav0(const std::string& dir);

struct EurocStereoLayout {
  std::string mav0;                // the mav0 folder
  EurocCameraSensor cam0, cam1;    // from cam0/sensor.yaml, cam1/sensor.yaml
  std::vector<ImagePair> frames;   // cam0 (a) / cam1 (b) images with equal stamps, time order
};

// Reads cam0 and cam1 (sensor.yaml, data.csv) of `mav0`. No images, or no pair with equal
// stamps: InputError naming the data.csv.
EurocStereoLayout ReadEurocStereoLayout(const std::string& mav0);

}  // namespace viqu::io

#pragma once
// An IMU's samples from a EuRoC imu0/data.csv (the layout viqu's recordings also write):
// "timestamp [ns], w_x, w_y, w_z [rad/s], a_x, a_y, a_z [m/s^2]" in the IMU frame.
#include <string>
#include <vector>

#include "slam/measurements/imu_sample.h"

namespace viqu::io {

// Throws InputError naming FILE:LINE for a malformed row, a non-finite value or stamps that do
// not increase, and naming the file when it is missing or lists no sample.
std::vector<ImuSample> ReadImuCsv(const std::string& path);

}  // namespace viqu::io

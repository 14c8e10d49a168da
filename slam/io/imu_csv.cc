#include "slam/io/imu_csv.h"

#include "common/errors.h"
#include "slam/io/stamped_rows.h"

namespace viqu::io {

std::vector<ImuSample> ReadImuCsv(const std::string& path) {
  std::vector<ImuSample> out;
  ReadStampedRows(path, 6, [&](int64_t t, const std::vector<double>& v, const TextTableReader&) {
    ImuSample s;
    s.t_ns = t;
    s.gyro_i = Eigen::Vector3d(v[0], v[1], v[2]);
    s.accel_i = Eigen::Vector3d(v[3], v[4], v[5]);
    out.push_back(s);
  });
  if (out.empty()) throw InputError(path + ": no IMU samples");
  return out;
}

}  // namespace viqu::io

#include "slam/io/proprioception_reader.h"

#include <filesystem>

#include "common/errors.h"
#include "slam/io/euroc_ground_truth.h"
#include "slam/io/euroc_layout.h"
#include "slam/io/imu_csv.h"
#include "slam/io/stamped_rows.h"

namespace viqu::io {
namespace {

namespace fs = std::filesystem;

bool Bit(double x, const TextTableReader& table) {
  if (x != 0 && x != 1) table.Fail("a contact field must be 0 or 1");
  return x == 1;
}

}  // namespace

std::optional<Proprioception> ReadViquProprioception(const std::string& dir) {
  std::error_code ec;
  fs::path mav0 = fs::path(dir) / "dataset" / "mav0";
  if (!fs::is_directory(mav0, ec)) mav0 = fs::path(dir) / "mav0";
  for (const char* need : {"imu0/data.csv", "joints0/data.csv", "contact0/data.csv", "robot.urdf"}) {
    if (!fs::exists(mav0 / need, ec)) return std::nullopt;
  }
  Proprioception p;
  p.urdf_path = (mav0 / "robot.urdf").string();
  p.imu = ReadImuCsv((mav0 / "imu0" / "data.csv").string());
  // joints0: positions, velocities, contacts, then (since torque sensing) the servos' torques.
  constexpr size_t kEncoderColumns = 2 * kNumJoints + kNumLegs;
  ReadStampedRows((mav0 / "joints0" / "data.csv").string(), kEncoderColumns,
           [&](int64_t t, const std::vector<double>& v, const TextTableReader& table) {
             JointState j;
             j.t_ns = t;
             for (int i = 0; i < kNumJoints; ++i) {
               j.position_rad[i] = v[i];
               j.velocity_rad_s[i] = v[kNumJoints + i];
             }
             for (int i = 0; i < kNumLegs; ++i) j.contact[i] = Bit(v[2 * kNumJoints + i], table);
             j.has_torque = v.size() > kEncoderColumns;
             if (j.has_torque) {
               for (int i = 0; i < kNumJoints; ++i) j.torque_nm[i] = v[kEncoderColumns + i];
             }
             p.joints.push_back(j);
           },
           kEncoderColumns + kNumJoints);
  ReadStampedRows((mav0 / "contact0" / "data.csv").string(), 2 * kNumLegs,
           [&](int64_t t, const std::vector<double>& v, const TextTableReader& table) {
             ContactReading touch{t, {}}, planned{t, {}};
             for (int i = 0; i < kNumLegs; ++i) {
               touch.stance[i] = Bit(v[i], table);
               planned.stance[i] = Bit(v[kNumLegs + i], table);
             }
             p.touch.push_back(touch);
             p.planned.push_back(planned);
           });
  p.T_body_cam0 = ReadEurocStereoLayout(mav0.string()).cam0.T_B_S;
  const fs::path gt = mav0 / "state_groundtruth_estimate0" / "data.csv";
  if (fs::exists(gt, ec)) {
    const std::vector<StampedPose> body = ReadEurocGroundTruth(gt.string());
    if (!body.empty()) p.body_at_start = body.front();
  }
  return p;
}

}  // namespace viqu::io

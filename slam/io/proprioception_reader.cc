#include "slam/io/proprioception_reader.h"

#include <filesystem>

#include "common/errors.h"
#include "slam/io/euroc_ground_truth.h"
#include "slam/io/euroc_layout.h"
#include "slam/io/number_parsing.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {
namespace {

namespace fs = std::filesystem;

// Rows of a data.csv: a stamp (ns, strictly increasing) and `n` numbers.
template <typename F>
void ReadRows(const fs::path& path, size_t n, F&& on_row) {
  TextTableReader table(path.string(), ',');
  std::vector<std::string> f;
  std::vector<double> v(n);
  int64_t last = 0;
  bool first = true;
  while (table.Next(&f)) {
    if (f.size() != n + 1) {
      table.Fail("expected " + std::to_string(n + 1) + " fields, got " + std::to_string(f.size()));
    }
    int64_t t = 0;
    if (!ParseInt64(f[0], &t)) table.Fail("timestamp '" + f[0] + "' is not an integer (ns)");
    if (!first && t <= last) table.Fail("timestamp " + f[0] + " does not follow " + std::to_string(last));
    for (size_t i = 0; i < n; ++i) {
      if (!ParseFiniteDouble(f[i + 1], &v[i])) table.Fail("field " + std::to_string(i + 2) + " '" + f[i + 1] + "' is not a finite number");
    }
    on_row(t, v, table);
    last = t;
    first = false;
  }
}

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
  ReadRows(mav0 / "imu0" / "data.csv", 6, [&](int64_t t, const std::vector<double>& v, const TextTableReader&) {
    ImuSample s;
    s.t_ns = t;
    s.gyro_i = Eigen::Vector3d(v[0], v[1], v[2]);
    s.accel_i = Eigen::Vector3d(v[3], v[4], v[5]);
    p.imu.push_back(s);
  });
  ReadRows(mav0 / "joints0" / "data.csv", 2 * kNumJoints + kNumLegs,
           [&](int64_t t, const std::vector<double>& v, const TextTableReader& table) {
             JointState j;
             j.t_ns = t;
             for (int i = 0; i < kNumJoints; ++i) {
               j.position_rad[i] = v[i];
               j.velocity_rad_s[i] = v[kNumJoints + i];
             }
             for (int i = 0; i < kNumLegs; ++i) j.contact[i] = Bit(v[2 * kNumJoints + i], table);
             p.joints.push_back(j);
           });
  ReadRows(mav0 / "contact0" / "data.csv", 2 * kNumLegs,
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

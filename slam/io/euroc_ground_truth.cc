#include "slam/io/euroc_ground_truth.h"

#include <cmath>

#include "slam/io/number_parsing.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {

std::vector<StampedPose> ReadEurocGroundTruth(const std::string& csv_path) {
  TextTableReader table(csv_path, ',');
  std::vector<StampedPose> out;
  std::vector<std::string> f;
  while (table.Next(&f)) {
    if (f.size() < 8) table.Fail("expected at least 8 columns 't_ns, px, py, pz, qw, qx, qy, qz'");
    StampedPose p;
    if (!ParseInt64(f[0], &p.t_ns)) table.Fail("timestamp '" + f[0] + "' is not an integer (ns)");
    double v[7];
    for (int i = 0; i < 7; ++i) {
      if (!ParseFiniteDouble(f[i + 1], &v[i])) {
        table.Fail("column " + std::to_string(i + 2) + " '" + f[i + 1] + "' is not a finite number");
      }
    }
    p.p_w_x = Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) table.Fail("quaternion is not unit length");
    p.q_w_x = q.normalized();
    if (!out.empty() && p.t_ns <= out.back().t_ns) {
      table.Fail(std::string(p.t_ns < out.back().t_ns ? "timestamp goes backwards" : "timestamp repeats"));
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace viqu::io

#include "slam/eval/trajectory.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/input_file.h"

namespace viqu::eval {

namespace {

// Bounds on what a trajectory line may hold. Stamps become int64 nanoseconds, which end at
// 9.22e9 s. Positions of a robot's trajectory stay far inside 1e6 m (1000 km); squares of values
// near 1e154 overflow a double, so far larger ones would give an infinite error.
constexpr long double kMaxStampS = 9.2e9L;
constexpr double kMaxPositionM = 1e6;
// The largest trajectory file read (bytes): a pose line is under 120 bytes, so this holds ten
// hours at 1 kHz; the bound keeps a wrong path from filling memory.
constexpr uintmax_t kMaxTrajectoryFileBytes = uintmax_t{4} << 30;

}  // namespace

Trajectory ReadTumTrajectory(const std::string& path) {
  InputLines in(path, kMaxTrajectoryFileBytes, "trajectory file");
  Trajectory out;
  std::string line;
  int line_no = 0;
  while (in.Next(&line)) {
    line_no = in.line();
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    // Separated by spaces, tabs or commas, as TUM's associate.py reads them.
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ss(line);
    std::vector<std::string> fields;
    for (std::string f; ss >> f;) fields.push_back(f);
    long double t = 0;
    double v[7];
    bool numbers = fields.size() == 8;
    for (size_t k = 0; numbers && k < 8; ++k) {
      // strtold reads "nan" and "inf" too, which the check below names.
      // The stamp in long double (nanoseconds of 1e9 s stamps), the pose straight to double.
      char* end = nullptr;
      if (k == 0) {
        t = std::strtold(fields[k].c_str(), &end);
      } else {
        v[k - 1] = std::strtod(fields[k].c_str(), &end);
      }
      numbers = end != fields[k].c_str() && *end == '\0';
    }
    if (!numbers) {
      throw InputError(path + ":" + std::to_string(line_no) + ": expected 8 numbers 't tx ty tz qx qy qz qw'");
    }
    bool finite = std::isfinite(static_cast<double>(t));
    for (double x : v) finite = finite && std::isfinite(x);
    if (!finite) throw InputError(path + ":" + std::to_string(line_no) + ": value is not a finite number");
    if (std::fabs(t) > kMaxStampS) {
      throw InputError(path + ":" + std::to_string(line_no) + ": timestamp outside +-9.2e9 s");
    }
    for (int k = 0; k < 3; ++k) {
      if (std::fabs(v[k]) > kMaxPositionM) {
        throw InputError(path + ":" + std::to_string(line_no) + ": position outside +-1e6 m");
      }
    }
    StampedPose p;
    p.t_ns = std::llround(t * 1e9L);
    p.p_w_x = Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw InputError(path + ":" + std::to_string(line_no) + ": quaternion is not unit length");
    }
    p.q_w_x = q.normalized();
    if (!out.empty() && p.t_ns < out.back().t_ns) {
      throw InputError(path + ":" + std::to_string(line_no) + ": timestamp goes backwards");
    }
    if (!out.empty() && p.t_ns == out.back().t_ns) {
      throw InputError(path + ":" + std::to_string(line_no) + ": timestamp repeats the previous pose's");
    }
    out.push_back(p);
  }
  return out;
}

std::vector<std::pair<size_t, size_t>> Associate(const Trajectory& est, const Trajectory& gt, double max_diff_s) {
  struct Candidate {
    int64_t diff_ns;
    size_t i, j;
  };
  const int64_t max_ns = std::llround(max_diff_s * 1e9);
  std::vector<Candidate> cand;
  // Both are sorted by time: for each estimate, scan the window of ground truth within max_ns.
  size_t lo = 0;
  for (size_t i = 0; i < est.size(); ++i) {
    while (lo < gt.size() && gt[lo].t_ns <= est[i].t_ns - max_ns) ++lo;
    for (size_t j = lo; j < gt.size() && gt[j].t_ns < est[i].t_ns + max_ns; ++j) {
      cand.push_back({std::llabs(est[i].t_ns - gt[j].t_ns), i, j});
    }
  }
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) {
    return a.diff_ns < b.diff_ns;
  });
  std::vector<bool> used_est(est.size()), used_gt(gt.size());
  std::vector<std::pair<size_t, size_t>> pairs;
  for (const Candidate& c : cand) {
    if (used_est[c.i] || used_gt[c.j]) continue;
    used_est[c.i] = used_gt[c.j] = true;
    pairs.emplace_back(c.i, c.j);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace viqu::eval

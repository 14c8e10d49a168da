#include "sim/trajectory_writer.h"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>

namespace viqu::sim {
namespace {

// " %.9f", without the sign of a value that rounds to zero ("-0.000000000").
std::string Field(double v) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), " %.9f", v);
  std::string s = buf;
  if (s == " -0.000000000") s = " 0.000000000";
  return s;
}

double RoundedAsWritten(double v) { return std::strtod(Field(v).c_str(), nullptr); }

}  // namespace

StampedPose AsReadBack(const StampedPose& pose) {
  Eigen::Quaterniond q = pose.q_w_x.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  StampedPose out = pose;
  for (int i = 0; i < 3; ++i) out.p_w_x[i] = RoundedAsWritten(pose.p_w_x[i]);
  out.q_w_x = Eigen::Quaterniond(RoundedAsWritten(q.w()), RoundedAsWritten(q.x()), RoundedAsWritten(q.y()),
                                 RoundedAsWritten(q.z()))
                  .normalized();
  return out;
}

std::string FormatSeconds(int64_t t_ns) {
  const bool negative = t_ns < 0;
  const uint64_t magnitude = negative ? 0 - static_cast<uint64_t>(t_ns) : static_cast<uint64_t>(t_ns);
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%s%" PRIu64 ".%09" PRIu64, negative ? "-" : "",
                magnitude / 1000000000u, magnitude % 1000000000u);
  return buf;
}

TrajectoryWriter::TrajectoryWriter(const std::string& path)
    : file_(std::make_unique<AtomicOutputFile>(path)) {
  file_->Write("# timestamp tx ty tz qx qy qz qw\n");
}

void TrajectoryWriter::Add(const StampedPose& pose) {
  // q and -q are the same rotation: print the one with qw >= 0 so that lines do not flip sign.
  Eigen::Quaterniond q = pose.q_w_x.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d& p = pose.p_w_x;
  std::string line = FormatSeconds(pose.t_ns);
  for (double v : {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()}) line += Field(v);
  file_->Write(line + "\n");
  ++lines_;
}

void TrajectoryWriter::Add(int64_t t_ns, const Eigen::Isometry3d& T_w_x) {
  StampedPose pose;
  pose.t_ns = t_ns;
  pose.q_w_x = Eigen::Quaterniond(T_w_x.rotation());
  pose.p_w_x = T_w_x.translation();
  Add(pose);
}

void TrajectoryWriter::Close() { file_->Commit(); }

}  // namespace viqu::sim

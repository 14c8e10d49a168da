#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "common/atomic_output_file.h"
#include "slam/measurements/ground_truth_pose.h"

namespace viqu::sim {

// Writes a trajectory in TUM format, one pose per line: "t tx ty tz qx qy qz qw" with t in
// seconds (9 decimals, exact from the nanosecond stamp), positions in metres and a unit
// quaternion with qw >= 0. The file is written under a temporary name and renamed by Close(); destroyed
// without Close(), the writer removes the temporary file and leaves no file under `path`.
class TrajectoryWriter {
 public:
  // Opens the temporary file next to `path`. Throws RunError when it cannot.
  explicit TrajectoryWriter(const std::string& path);

  // Appends the pose T_w_x (frame x in the world) at pose.t_ns.
  void Add(const StampedPose& pose);
  void Add(int64_t t_ns, const Eigen::Isometry3d& T_w_x);
  // Finishes the file and renames it onto its final name. Throws RunError on failure.
  void Close();

  size_t size() const { return lines_; }
  const std::string& path() const { return file_->final_path(); }

 private:
  std::unique_ptr<AtomicOutputFile> file_;  // the output, under its temporary name until Close()
  size_t lines_ = 0;                        // poses written
};

// `pose` as a reader gets it back from this writer's file (and from a recording's EuRoC ground
// truth, which prints the same 9 decimals): each number rounded as written and read back, the
// quaternion normalised as the readers do. A live run anchors its estimators at this pose so that
// a replay of its recording, anchored at the pose read from the file, starts from the same bits.
StampedPose AsReadBack(const StampedPose& pose);

// "12.345678901" from 12345678901 ns (exact, also for negative stamps).
std::string FormatSeconds(int64_t t_ns);

}  // namespace viqu::sim

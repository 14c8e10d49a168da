#pragma once
// Trajectories in TUM format ("t tx ty tz qx qy qz qw", t in seconds) and their evaluation:
// timestamp association as TUM's associate.py, Umeyama alignment, ATE and RPE.
#include <string>
#include <vector>

#include "slam/measurements/ground_truth_pose.h"

namespace viqu::eval {

using Trajectory = std::vector<StampedPose>;

// Reads a TUM trajectory file. Lines starting with '#' and blank lines are skipped. Throws
// viqu::InputError naming the file and line for a missing file, a malformed line, a NaN value, or
// a timestamp that goes backwards.
Trajectory ReadTumTrajectory(const std::string& path);

// Index pairs (into est, into gt) matched as associate.py does: candidate pairs whose stamps
// differ by less than max_diff_s, taken greedily by smallest difference, each stamp used once;
// returned in increasing time of `est`.
std::vector<std::pair<size_t, size_t>> Associate(const Trajectory& est, const Trajectory& gt,
                                                 double max_diff_s = 0.02);

}  // namespace viqu::eval

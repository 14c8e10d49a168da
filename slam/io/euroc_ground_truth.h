#pragma once
#include <string>
#include <vector>

#include "slam/measurements/ground_truth_pose.h"

namespace viqu::io {

// Reads EuRoC's state_groundtruth_estimate0/data.csv: "t_ns, p_RS_R xyz, q_RS wxyz, ..." (the
// velocity and bias columns are ignored), i.e. the IMU frame S in the world R. Malformed row,
// non-unit quaternion, stamp that does not increase: InputError "CSV:LINE: ...".
std::vector<StampedPose> ReadEurocGroundTruth(const std::string& csv_path);

}  // namespace viqu::io

#pragma once
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// Reads seg0/instances.csv of a viqu recording: "id,category,name" (the name may hold commas).
// Malformed row, unknown category, repeated id: InputError "CSV:LINE: ...".
std::vector<SegmentInstance> ReadSegmentInstances(const std::string& csv_path);

// The entries of `all` whose id occurs in `ids` (CV_16U), in order of id.
std::vector<SegmentInstance> InstancesPresent(const cv::Mat& ids, const std::vector<SegmentInstance>& all);

}  // namespace viqu::io

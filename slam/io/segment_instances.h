#pragma once
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// Reads seg0/instances.csv of a viqu recording, or the instances.csv of a masks folder:
// "id,category,name" (the name may hold commas); '#' comment lines and a first row that is
// exactly "id,category,name" (a header) are skipped.
// Malformed row, unknown category, repeated id: InputError "CSV:LINE: ...".
std::vector<SegmentInstance> ReadSegmentInstances(const std::string& csv_path);

// The entries of `all` whose id occurs in `ids` (CV_16U), in order of id.
std::vector<SegmentInstance> InstancesPresent(const cv::Mat& ids, const std::vector<SegmentInstance>& all);

}  // namespace viqu::io

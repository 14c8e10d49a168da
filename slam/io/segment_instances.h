#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// The category named `name` (CategoryName's words); false for any other word.
bool ParseCategory(const std::string& name, Category* out);

// Reads seg0/instances.csv of a viqu recording, or the instances.csv of a masks folder:
// "id,category,name" (the name may hold commas); '#' comment lines and a first row that is
// exactly "id,category,name" (a header) are skipped.
// Malformed row, unknown category, repeated id: InputError "CSV:LINE: ...".
std::vector<SegmentInstance> ReadSegmentInstances(const std::string& csv_path);

// Reads seg0/frame_instances.csv of a viqu recording (sim/euroc_recorder.h): per segmentation
// image stamp (ns), the frame's instance list, "timestamp [ns],id,category,name" (the name may
// hold commas), '#' comment lines skipped. Each list is returned in order of id; a stamp without
// rows had an empty list. Malformed row, unknown category, an id listed twice for one stamp, or
// stamps out of order (rows of one stamp must be together, stamps increasing): InputError
// "CSV:LINE: ...".
std::map<int64_t, std::vector<SegmentInstance>> ReadFrameInstances(const std::string& csv_path);

// Throws InputError naming `image_path` and `list_what` when `ids` (CV_16U) holds a non-zero id
// that `listed` has no entry for.
void CheckIdsListed(const cv::Mat& ids, const std::vector<SegmentInstance>& listed, const std::string& image_path,
                    const std::string& list_what);

// The entries of `all` whose id occurs in `ids` (CV_16U), in order of id.
std::vector<SegmentInstance> InstancesPresent(const cv::Mat& ids, const std::vector<SegmentInstance>& all);

}  // namespace viqu::io

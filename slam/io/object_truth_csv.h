#pragma once
// The movable objects' truth of a viqu recording, mav0/objects0/data.csv (sim/euroc_recorder.h),
// so that `viqu slam --format viqu` scores the dynamic-object decisions of a replay as its live
// run scored them (dynamic.csv's truth columns, dynamic.precision / recall / latency).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slam/measurements/object_truth.h"

namespace viqu::io {

// Per camera frame stamp (ns), the objects' truth; a frame with no row has none visible.
using ObjectTruthStream = std::map<int64_t, std::vector<ObjectTruth>>;

// Reads DIR/dataset/mav0/objects0/data.csv (a run folder) or DIR/mav0/objects0/data.csv (a
// dataset folder): nothing when the recording has no such stream (recorded before it existed,
// or without segmentation). Malformed rows, unknown categories, stamps going backwards:
// InputError naming FILE:LINE.
std::optional<ObjectTruthStream> ReadViquObjectTruth(const std::string& dir);

}  // namespace viqu::io

#pragma once
// Scores the dynamic-object stage against the simulator's truth: dynamic.csv (one row per object
// and frame) and the dynamic.* keys of metrics.json (DESIGN.md). Offline replays have no truth:
// their rows leave the truth columns empty and the metrics hold only what needs none, unless the
// recording kept the truth (objects0, slam/io/object_truth_csv.h).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/atomic_output_file.h"
#include "common/json_writer.h"
#include "sim/obstacles.h"
#include "slam/core/dynamic_objects.h"
#include "slam/measurements/object_truth.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::runner {

// A person pausing for a second between strides is still a moving object: truth counts an object
// as moving when it moved more than kTruthMoveM over the last kTruthWindowS.
constexpr double kTruthWindowS = 1.0;  // (s)
constexpr double kTruthMoveM = 0.01;   // (m)
// Precision and recall count object-frames with at least this many features in the object's
// mask (issue 7): fewer cannot carry a decision worth scoring.
constexpr int kScoredMinFeatures = 20;

// The truth of every movable obstacle visible in `ideal` (the rendered frame before the detector
// model) at simulated time t_s.
std::vector<ObjectTruth> ObjectTruthOf(const StereoFrame& ideal, const sim::ObstacleSet& obstacles, double t_s);

class DynamicScore {
 public:
  explicit DynamicScore(const std::string& csv_path);

  // One frame: the SLAM system's object reports and, live, the truth (null offline).
  void Add(int64_t t_ns, const std::vector<slam::ObjectReport>& reports, const std::vector<ObjectTruth>* truth);

  // Commits dynamic.csv and adds the dynamic.* keys to `json`. `judged`: whether a dynamic
  // stage judged objects at all (false for method none and mode visual: precision and recall are
  // then null, not 0: nothing was judged, so nothing was missed).
  void Finish(JsonWriter* json, bool judged = true);

 private:
  struct ObjectTimeline {
    std::string category;
    double moving_from_s = -1;       // first frame seen (features > 0) while truly moving (s)
    double detected_s = -1;          // first frame judged dynamic at or after that (s)
  };
  std::unique_ptr<AtomicOutputFile> csv_;
  bool have_truth_ = false;
  int64_t tp_ = 0, fp_ = 0, fn_ = 0, tn_ = 0;  // scored object-frames
  int64_t static_features_ = 0, static_kept_ = 0;
  int64_t moving_features_ = 0, moving_dropped_ = 0;
  int64_t decided_frames_ = 0, object_frames_ = 0;
  std::map<std::string, ObjectTimeline> timelines_;  // by object name
};

}  // namespace viqu::runner

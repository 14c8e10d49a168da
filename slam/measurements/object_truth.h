#pragma once
// What the simulator knows about one movable object in one camera frame: the truth the
// dynamic-object stage is scored against (runner/dynamic_score.h). Live runs compute it; a
// recording keeps it as mav0/objects0/data.csv (sim/euroc_recorder.h) so that a replay is scored
// as its live run was. The estimator never reads it.
#include <string>

#include "slam/measurements/stereo_frame.h"

namespace viqu {

struct ObjectTruth {
  std::string name;                  // obstacle name from the scenario
  Category category = Category::kBackground;
  int visible_px = 0;                // pixels in the ideal (detector-free) instance image of the left camera
  bool moving = false;               // moved more than kTruthMoveM within the last kTruthWindowS (dynamic_score.h)
};

}  // namespace viqu

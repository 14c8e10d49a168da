#pragma once
#include "apps/cli.h"

namespace viqu::app {

// `viqu slam DATASET_DIR [--format viqu|euroc|tum] [--config FILE] [--out DIR]`: replays a
// dataset through SLAM and writes OUT/trajectory_est.txt, OUT/trajectory_gt.txt (when the dataset
// has ground truth), OUT/slam_settings.yaml and OUT/metrics.json. Returns the exit code.
int RunSlamCommand(const SlamArgs& args);

}  // namespace viqu::app

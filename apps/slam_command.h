#pragma once
#include "apps/cli.h"

namespace viqu::app {

// `viqu slam DATASET_DIR [--format viqu|euroc|tum] [--config FILE] [--camera FILE] [--out DIR]
// [--force] [--masks DIR] [--set key.path=value ...]`: replays a dataset (with the instance masks of DIR when given)
// through SLAM with the settings file plus the overrides, and writes OUT/trajectory_est.txt,
// OUT/trajectory_gt.txt (when the dataset has ground truth), OUT/slam_settings.yaml (resolved)
// and OUT/metrics.json, then the completion marker (common/run_folder.h). `command_line` is
// recorded in the marker. Returns the exit code.
int RunSlamCommand(const SlamArgs& args, const std::string& command_line = "");

}  // namespace viqu::app

#pragma once
// Local bundle adjustment: the poses of a keyframe and its best covisible keyframes and the map
// points they see, against all observations of those points (keyframes outside the window are
// held fixed), with a Huber kernel. Observations that stay outside the chi-square 95% threshold
// afterwards are removed from the map.
#include <mutex>

#include "slam/core/camera.h"

namespace viqu::slam {

class KeyFrame;
class Map;

struct LocalBaOptions {
  int window = 10;          // optimised keyframes, the new one included
  int iterations = 10;      // Levenberg-Marquardt iterations
  double huber_px = 2.447;  // kernel width (px) for monocular residuals
  int max_fixed = 30;       // fixed keyframes at most (those sharing the most points)
};

struct LocalBaResult {
  int keyframes = 0, fixed_keyframes = 0, points = 0, observations = 0, removed_observations = 0;
  double initial_cost = 0, final_cost = 0;
};

// Runs local BA around `kf`. Takes `map_mutex` (the Map's) while reading and writing the map and
// releases it while solving, so tracking can go on in real-time mode.
LocalBaResult LocalBundleAdjustment(const StereoCamera& cam, const LocalBaOptions& opt, KeyFrame* kf,
                                    std::mutex* map_mutex);

}  // namespace viqu::slam

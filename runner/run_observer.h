#pragma once
// A look into a run while it goes (the interactive viewer, `viqu view`). RunScenario calls the
// observer on the simulation thread after each camera frame has been through the estimator
// stage, with the estimator stage run inline (RunOptions::sequential), so that the simulation,
// the frame and the estimator's state all belong to the same instant. An observer sees, never
// changes: the run's outputs are the bytes of the same run without one.
#include <cstdint>

#include "slam/core/slam_system.h"
#include "slam/eval/trajectory.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {
class World;
}

namespace viqu::runner {

class SlamRun;

struct ObservedFrame {
  int64_t index = 0;                         // camera frame number, from 0
  double t_s = 0;                            // simulated time of the frame (s)
  double duration_s = 0;                     // the scenario's length (s)
  const sim::World* world = nullptr;         // the simulation at the frame's time
  const StereoFrame* frame = nullptr;        // the images as the estimator got them
  const slam::TrackResult* track = nullptr;  // null without SLAM
  const SlamRun* slam = nullptr;             // null without SLAM: estimate and map
  const eval::Trajectory* ground_truth = nullptr;  // left camera in the world, every frame so far
  const eval::Trajectory* leg_odometry = nullptr;  // leg odometry + IMU alone (slam.mode full), else null
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // Called after each camera frame; may block (a paused viewer). Returns false to end the run
  // there: the outputs so far are finished and the run folder is marked incomplete, as after a
  // stop signal, and RunScenario returns 0.
  virtual bool OnFrame(const ObservedFrame& f) = 0;
  // Called once after the run folder is finished (complete or not), with the last frame seen
  // (its `frame` and `track` are null); the simulation is still alive. May block.
  virtual void OnRunEnd(const ObservedFrame& last) = 0;
};

}  // namespace viqu::runner

#pragma once
// Local mapping after each new keyframe: links the keyframe's matches into the map, culls weak
// recent map points, triangulates new points with covisible keyframes, fuses duplicates, runs
// local bundle adjustment and culls redundant keyframes. In sync mode Process() runs inline; in
// realtime mode keyframes are queued for a mapping thread.
#include <condition_variable>
#include <deque>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/local_ba.h"
#include "slam/core/matcher.h"
#include "slam/settings/slam_settings.h"

namespace viqu::slam {

class KeyFrame;
class Map;
class MapPoint;

class LocalMapper {
 public:
  LocalMapper(const StereoCamera& cam, const SlamSettings& settings, Map* map);
  ~LocalMapper();
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // Hands a new keyframe to mapping: processed now (sync) or queued (realtime).
  void Insert(KeyFrame* kf);
  // Realtime: waits until the queue is empty. Sync: no-op.
  void WaitIdle();
  // Realtime: keyframes waiting (the tracker makes fewer keyframes while mapping is behind).
  size_t Queued() const;

  // Points created for `kf` at its creation (the stereo points), to be watched by culling.
  void AddRecentPoints(const std::vector<MapPoint*>& points);

  // When mapping is idle (always in sync mode; in realtime mode when nothing is queued or being
  // processed, which stays so until the next Insert from the caller's thread), adds the keyframes
  // and points it holds (queue, probation list) and returns true; returns false while it works.
  bool PinnedIfIdle(std::vector<const KeyFrame*>* keyframes, std::vector<const MapPoint*>* points) const;

  const std::vector<double>& ba_ms() const { return ba_ms_; }

 private:
  void Process(KeyFrame* kf);  // takes the map mutex itself where it touches the map
  void LinkObservations(KeyFrame* kf);
  void CullRecentPoints(KeyFrame* kf);
  int TriangulateNewPoints(KeyFrame* kf);
  void FuseWithNeighbours(KeyFrame* kf);
  void CullKeyFrames(KeyFrame* kf);
  void ThreadLoop();

  StereoCamera cam_;
  SlamSettings settings_;
  Map* map_;
  Matcher matcher_;
  LocalBaOptions ba_opt_;
  std::list<MapPoint*> recent_;          // points still on probation
  std::vector<double> ba_ms_;            // local BA wall times (ms)

  bool realtime_ = false;
  mutable std::mutex queue_mutex_;
  std::condition_variable queue_cv_, idle_cv_;
  std::deque<KeyFrame*> queue_;
  bool busy_ = false, stop_ = false;
  std::thread thread_;
};

}  // namespace viqu::slam

#pragma once
// The map: keyframes, map points and the covisibility between keyframes. The Map owns every
// object. Culled ones are flagged `bad` and stay allocated while anything outside the map's own
// links may still hold them (the tracker's frames and local map, the mapper's queue and probation
// list); Reclaim() frees the rest, so a long run's memory stays bounded. All access happens under
// Map::mutex.
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "slam/core/camera.h"
#include "slam/core/frame.h"

namespace viqu::slam {

class KeyFrame;

// Orders keyframes by id, so that iteration over keyframe-keyed containers (and with it every
// result) does not depend on where the keyframes happen to be allocated.
struct KeyFrameIdLess {
  bool operator()(const KeyFrame* a, const KeyFrame* b) const;
};
template <class V>
using KeyFrameMap = std::map<KeyFrame*, V, KeyFrameIdLess>;

// The same map kept as a vector sorted by keyframe id, for the many small ones (a map point's
// few observations): 16 bytes an entry against a 48-byte tree node. Inserting or erasing moves
// the entries after it and invalidates iterators.
template <class V>
class KeyFrameFlatMap {
 public:
  using value_type = std::pair<KeyFrame*, V>;
  using iterator = typename std::vector<value_type>::iterator;
  using const_iterator = typename std::vector<value_type>::const_iterator;

  iterator begin() { return entries_.begin(); }
  iterator end() { return entries_.end(); }
  const_iterator begin() const { return entries_.begin(); }
  const_iterator end() const { return entries_.end(); }
  size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  size_t capacity() const { return entries_.capacity(); }
  void clear() { entries_.clear(); }

  iterator find(const KeyFrame* k) { return Find(entries_.begin(), entries_.end(), k); }
  const_iterator find(const KeyFrame* k) const { return Find(entries_.begin(), entries_.end(), k); }
  size_t count(const KeyFrame* k) const { return find(k) != end() ? 1 : 0; }
  const V& at(const KeyFrame* k) const {
    auto it = find(k);
    if (it == end()) throw std::out_of_range("KeyFrameFlatMap::at: no such keyframe");
    return it->second;
  }
  // The value of `k`, inserted as V() at its place if absent.
  V& operator[](KeyFrame* k) {
    auto it = LowerBound(entries_.begin(), entries_.end(), k);
    if (it == entries_.end() || it->first != k) it = entries_.insert(it, value_type(k, V()));
    return it->second;
  }
  iterator erase(const_iterator it) { return entries_.erase(it); }

 private:
  template <class It>
  static It LowerBound(It first, It last, const KeyFrame* k) {
    return std::lower_bound(first, last, k, [](const value_type& e, const KeyFrame* key) { return KeyFrameIdLess()(e.first, key); });
  }
  template <class It>
  static It Find(It first, It last, const KeyFrame* k) {
    const It it = LowerBound(first, last, k);
    return it != last && it->first == k ? it : last;
  }
  std::vector<value_type> entries_;
};

class MapPoint {
 public:
  MapPoint(int64_t id, const Eigen::Vector3d& p_w, KeyFrame* ref) : id(id), p_w(p_w), reference(ref) {}

  int64_t id;
  Eigen::Vector3d p_w;                     // position in world (m)
  KeyFrame* reference;                     // keyframe that created it
  KeyFrameFlatMap<int> observations;       // keyframe -> feature index (ordered by keyframe id)
  // The observation descriptor closest to all others (ORB: 32 bytes), a copy: a point outlives
  // the keyframe it was taken from.
  std::array<uint8_t, 32> descriptor{};
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // mean viewing direction (unit)
  double min_distance = 0, max_distance = 0;         // scale-invariance range (m)
  int visible = 1;                         // frames where it projected into the image
  int found = 1;                           // frames where it was matched
  int64_t first_keyframe_id = 0;
  uint16_t object = 0;                     // segmentation instance of the feature that created it (0 = none)
  bool bad = false;
  // A point of an object that has since moved (Map::RetireObjectPoints): it keeps the observations
  // of the keyframes taken while the object stood there, which BA still uses, and is never matched,
  // fused or observed again.
  bool retired = false;
  // Whether tracking and fusion may match it: neither bad nor retired.
  bool Matchable() const { return !bad && !retired; }
  // The tracker's own bookkeeping (read and written by the tracking thread only): the index of
  // the last frame whose local map took this point, so that gathering the local map needs no
  // set of pointers (thousands of tree nodes a frame, which fragmented the heap over long runs).
  int64_t local_map_frame = -1;

  // Copies row `row` of `descriptors` (CV_8U, 32 bytes a row) into `descriptor`.
  void SetDescriptor(const cv::Mat& descriptors, int row);
  // Recomputes descriptor, normal and distance range from the observations.
  void UpdateFromObservations();
  // Pyramid level expected at distance `dist`.
  int PredictLevel(double dist, const FrameFeatures& f) const;
  // Observations counted as ORB-SLAM counts them: a stereo observation (with a right-image
  // match) counts twice, since it fixes the point on its own.
  int ObservationWeight() const;
  double FoundRatio() const { return static_cast<double>(found) / visible; }
};

class KeyFrame {
 public:
  KeyFrame(int64_t id, const Frame& frame);

  int64_t id;
  int64_t t_ns;
  std::shared_ptr<const FrameFeatures> features;
  std::vector<MapPoint*> points;           // map point per feature (nullptr: none)
  Eigen::Isometry3d T_c_w;                 // world -> camera
  KeyFrameMap<int> covisible;              // keyframe -> shared map points (>= threshold, or the best)
  bool bad = false;
  bool fixed = false;                      // the first keyframe anchors the map

  Eigen::Vector3d Center() const { return T_c_w.inverse().translation(); }
  // Keyframes sharing the most points, best first, at most n.
  std::vector<KeyFrame*> BestCovisible(size_t n) const;
  // Recomputes `covisible` from the map points' observations and updates the neighbours' lists.
  void UpdateConnections(int min_shared);
  // Its good points with at least this observation weight, retired ones included: when a moving
  // object's points are retired the tracked share of the reference keyframe falls and a keyframe
  // comes sooner, with new points on what is still static. (Leaving them out was measured worse:
  // standing_people `visual_dynamic`, seeds 1-9, 3.82 mm against 3.30; docs/MEASURED.md, session 35.)
  int TrackedPoints(int min_observations) const;
};

inline bool KeyFrameIdLess::operator()(const KeyFrame* a, const KeyFrame* b) const { return a->id < b->id; }

class Map {
 public:
  mutable std::mutex mutex;

  KeyFrame* AddKeyFrame(const Frame& frame);
  MapPoint* AddPoint(const Eigen::Vector3d& p_w, KeyFrame* ref);
  static void AddObservation(MapPoint* p, KeyFrame* kf, int idx);
  static void EraseObservation(MapPoint* p, KeyFrame* kf);
  // Flags the point bad and removes it from every keyframe.
  static void ErasePoint(MapPoint* p);
  // For segmentation instance `object` (> 0), which moved from `moving_from_ns` on: each good
  // point created from a feature on it loses the observations of keyframes taken from then on
  // and is retired (MapPoint::retired) if two or more are left, else erased (an onset before
  // every observation erases them all). Returns the number erased; `*retired` (may be null)
  // gets the number retired.
  int RetireObjectPoints(uint16_t object, int64_t moving_from_ns, int* retired);
  // Replaces `a` by `b` everywhere (duplicate fusion); `a` becomes bad.
  static void Replace(MapPoint* a, MapPoint* b);
  // Flags the keyframe bad, drops its observations and reconnects its neighbours.
  void EraseKeyFrame(KeyFrame* kf, int min_shared);

  // Frees every bad keyframe and map point that is not pinned (held by the tracker or the mapper:
  // SlamSystem collects them). Good points whose reference keyframe is freed forget it (as for a
  // bad reference). The order of the remaining objects is kept, and ids keep counting, so the
  // results do not change. Returns the number of objects freed.
  size_t Reclaim(const std::vector<const KeyFrame*>& pinned_keyframes, const std::vector<const MapPoint*>& pinned_points);
  int64_t keyframes_freed() const { return keyframes_freed_; }
  int64_t points_freed() const { return points_freed_; }

  const std::vector<std::unique_ptr<KeyFrame>>& keyframes() const { return keyframes_; }
  const std::vector<std::unique_ptr<MapPoint>>& points() const { return points_; }
  int GoodKeyFrames() const;
  int GoodPoints() const;
  // Good keyframes not in `exclude` whose camera centre lies within `radius_m` of the camera
  // `T_w_c` and whose optical axis is within `max_angle_deg` of its (180: any), nearest first
  // (ties by id), at most `max_count`.
  std::vector<KeyFrame*> NearbyKeyFrames(const Eigen::Isometry3d& T_w_c, double radius_m, double max_angle_deg,
                                         const std::set<KeyFrame*>& exclude, size_t max_count) const;
  // Heap bytes held by the keyframes and map points (held ones included), counted from their
  // sizes and the capacities of their containers; a tree node is counted at kTreeNodeBytes. An
  // account of where a run's memory goes, not a measurement of the allocator's use.
  size_t HeapBytes() const;

 private:
  std::vector<std::unique_ptr<KeyFrame>> keyframes_;
  std::vector<std::unique_ptr<MapPoint>> points_;
  int64_t next_keyframe_id_ = 0, next_point_id_ = 0;
  int64_t keyframes_freed_ = 0, points_freed_ = 0;
};

// Hamming distance of two 32-byte descriptors.
int DescriptorDistance(const cv::Mat& a, const cv::Mat& b);
int DescriptorDistance(const uint8_t* a, const uint8_t* b);

}  // namespace viqu::slam

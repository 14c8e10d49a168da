#pragma once
// Feature-to-map-point association: by projection with a predicted pose (motion model, local
// map, fusion), by descriptor (reference keyframe, relocalisation) and along epipolar lines
// between keyframes (triangulation of new points).
#include <utility>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/frame.h"

namespace viqu::slam {

class KeyFrame;
class MapPoint;

struct MatcherOptions {
  int max_hamming = 100;     // accepted descriptor distance (bits)
  int strict_hamming = 50;   // for matches without geometric prediction (bits)
  double ratio = 0.9;        // best / second best (projection searches)
  double bf_ratio = 0.75;    // best / second best (descriptor-only searches)
};

class Matcher {
 public:
  Matcher(const StereoCamera& cam, const MatcherOptions& opt) : cam_(cam), opt_(opt) {}

  // Projects the map points of `last` (with the pose already in `cur`) into `cur` and matches in
  // a window of `radius` px (scaled by the level). Returns new matches.
  int SearchByProjection(const Frame& last, double radius, Frame* cur) const;

  // Projects `points` (not yet matched in `cur`) into `cur`; window `radius` times the predicted
  // level's scale. Counts visibility in MapPoint::visible. Returns new matches.
  // `count_visible`: add one to `visible` of every point that projects into the frame (once per
  // tracked frame: a second, wider search of the same frame, or a relocalisation, passes false).
  int SearchLocalPoints(const std::vector<MapPoint*>& points, double radius, Frame* cur, bool count_visible) const;

  // Matches the map points of `kf` to features of `cur` by descriptor alone (no pose needed).
  int SearchByDescriptor(const KeyFrame& kf, Frame* cur) const;

  // Pairs of unmatched features (i in kf1, j in kf2) consistent with the epipolar geometry of
  // the two keyframes' poses.
  std::vector<std::pair<int, int>> SearchForTriangulation(const KeyFrame& kf1, const KeyFrame& kf2) const;

  // Projects `points` into `kf`: a point whose best feature has no map point is added as an
  // observation; one whose best feature has another map point replaces the weaker of the two.
  // Returns the number of fused points.
  int Fuse(KeyFrame* kf, const std::vector<MapPoint*>& points, double radius) const;

 private:
  StereoCamera cam_;
  MatcherOptions opt_;
};

}  // namespace viqu::slam

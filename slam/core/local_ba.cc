#include "slam/core/local_ba.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>
#include <vector>

#include "slam/core/map.h"
#include "slam/core/ba_solver.h"
#include "slam/core/reprojection_error.h"

namespace viqu::slam {
namespace {

struct Observation {
  KeyFrame* kf;
  MapPoint* point;
  int idx;
};

}  // namespace

LocalBaResult LocalBundleAdjustment(const StereoCamera& cam, const LocalBaOptions& opt, KeyFrame* kf,
                                    std::mutex* map_mutex) {
  LocalBaResult res;
  std::vector<KeyFrame*> local;
  std::vector<MapPoint*> points;
  std::vector<KeyFrame*> fixed;
  std::vector<Observation> obs;
  // The problem in arrays, in a fixed order (optimised keyframes first, then held ones; points by
  // id), so that the result does not depend on where the map's nodes live in the heap.
  BaProblem problem;
  std::unordered_map<const KeyFrame*, int> pose_index;
  std::unordered_map<const MapPoint*, int> point_index;
  {
    std::lock_guard<std::mutex> lock(*map_mutex);
    if (kf->bad) return res;
    local.push_back(kf);
    for (KeyFrame* n : kf->BestCovisible(opt.window - 1)) local.push_back(n);
    const std::set<KeyFrame*> local_set(local.begin(), local.end());
    std::set<MapPoint*> point_set;
    for (KeyFrame* k : local) {
      for (MapPoint* p : k->points) {
        if (p && !p->bad && point_set.insert(p).second) points.push_back(p);
      }
    }
    std::sort(points.begin(), points.end(), [](const MapPoint* a, const MapPoint* b) { return a->id < b->id; });
    KeyFrameMap<int> outside;  // keyframe -> observations of local points
    for (MapPoint* p : points) {
      for (const auto& [k, idx] : p->observations) {
        if (!k->bad && !local_set.count(k)) ++outside[k];
      }
    }
    std::vector<std::pair<int, KeyFrame*>> ranked;
    for (const auto& [k, n] : outside) ranked.emplace_back(n, k);
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second->id < b.second->id;
    });
    for (size_t i = 0; i < ranked.size() && static_cast<int>(i) < opt.max_fixed; ++i) fixed.push_back(ranked[i].second);
    const std::set<KeyFrame*> fixed_set(fixed.begin(), fixed.end());
    // Optimised: the window's keyframes except a segment's first (the gauge); held: the rest.
    for (bool free : {true, false}) {
      for (const std::vector<KeyFrame*>* group : {&local, &fixed}) {
        for (KeyFrame* k : *group) {
          const bool optimised = group == &local && !k->fixed;
          if (optimised != free || pose_index.count(k)) continue;
          pose_index.emplace(k, static_cast<int>(problem.poses.size()));
          problem.poses.push_back(k->T_c_w);
        }
      }
      if (free) problem.free_poses = static_cast<int>(problem.poses.size());
    }
    problem.points.reserve(points.size());
    for (MapPoint* p : points) {
      const int j = static_cast<int>(problem.points.size());
      point_index.emplace(p, j);
      problem.points.push_back(p->p_w);
      for (const auto& [k, idx] : p->observations) {
        if (k->bad || (!local_set.count(k) && !fixed_set.count(k))) continue;
        obs.push_back({k, p, idx});
        const FeaturePoint& kp = k->features->keypoints[idx];
        problem.observations.push_back({pose_index.at(k), j, kp.pt.x, kp.pt.y,
                                        cam.OptimiserColumn(k->features->u_right[idx], k->features->depth[idx]),
                                        1.0 / k->features->level_scale[kp.octave],
                                        cam.RightScale(k->features->depth[idx])});
      }
    }
  }
  res.keyframes = static_cast<int>(local.size());
  res.fixed_keyframes = static_cast<int>(fixed.size());
  res.points = static_cast<int>(points.size());
  res.observations = static_cast<int>(obs.size());
  if (points.empty()) return res;

  BaSolverOptions sopt;
  sopt.iterations = opt.iterations;
  sopt.huber_mono = opt.huber_px;
  sopt.huber_stereo = opt.huber_px * std::sqrt(kChi2Stereo / kChi2Mono);
  const BaSolverSummary summary = SolveBundleAdjustment(cam, sopt, &problem);
  res.initial_cost = 0.5 * summary.initial_cost;  // as Ceres reports it: half the sum
  res.final_cost = 0.5 * summary.final_cost;

  std::lock_guard<std::mutex> lock(*map_mutex);
  for (KeyFrame* k : local) {
    if (!k->bad && !k->fixed) k->T_c_w = problem.poses[pose_index.at(k)];
  }
  for (MapPoint* p : points) {
    if (p->bad) continue;
    p->p_w = problem.points[point_index.at(p)];
  }
  for (const Observation& o : obs) {
    if (o.point->bad || o.kf->bad) continue;
    auto it = o.point->observations.find(o.kf);
    if (it == o.point->observations.end() || it->second != o.idx) continue;
    if (!IsInlierObservation(cam, *o.kf->features, o.idx, o.kf->T_c_w * o.point->p_w)) {
      Map::EraseObservation(o.point, o.kf);
      ++res.removed_observations;
    }
  }
  for (MapPoint* p : points) {
    if (!p->bad) p->UpdateFromObservations();
  }
  return res;
}

}  // namespace viqu::slam

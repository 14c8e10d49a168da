#include "slam/core/local_ba.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>
#include <vector>

#include "slam/core/map.h"
#include "slam/core/reprojection_cost.h"
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
  // Parameter blocks in two arrays, in a fixed order (optimised keyframes, then fixed ones; points
  // by id): Ceres orders the blocks of an elimination group by their addresses (std::set<double*>),
  // so blocks in separately allocated map nodes made the Schur elimination order, and with it the
  // last digits of every result, depend on the heap (a replay differed from its live run).
  std::vector<std::array<double, 6>> pose_storage;
  std::vector<std::array<double, 3>> point_storage;
  std::unordered_map<const KeyFrame*, size_t> pose_index;
  std::unordered_map<const MapPoint*, size_t> point_index;
  auto pose_of = [&](const KeyFrame* k) { return pose_storage[pose_index.at(k)].data(); };
  auto point_of = [&](const MapPoint* p) { return point_storage[point_index.at(p)].data(); };
  std::vector<double> obs_u, obs_v, obs_ur, obs_w;
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
    for (const std::vector<KeyFrame*>* group : {&local, &fixed}) {
      for (KeyFrame* k : *group) {
        if (!pose_index.emplace(k, pose_storage.size()).second) continue;
        pose_storage.emplace_back();
        PoseToParams(k->T_c_w, pose_storage.back().data());
      }
    }
    point_storage.reserve(points.size());
    for (MapPoint* p : points) {
      point_index.emplace(p, point_storage.size());
      point_storage.push_back({p->p_w.x(), p->p_w.y(), p->p_w.z()});
      for (const auto& [k, idx] : p->observations) {
        if (k->bad || (!local_set.count(k) && !fixed_set.count(k))) continue;
        obs.push_back({k, p, idx});
        const cv::KeyPoint& kp = k->features->keypoints[idx];
        obs_u.push_back(kp.pt.x);
        obs_v.push_back(kp.pt.y);
        obs_ur.push_back(k->features->u_right[idx]);
        obs_w.push_back(1.0 / k->features->level_scale[kp.octave]);
      }
    }
  }
  res.keyframes = static_cast<int>(local.size());
  res.fixed_keyframes = static_cast<int>(fixed.size());
  res.points = static_cast<int>(points.size());
  res.observations = static_cast<int>(obs.size());
  if (points.empty()) return res;

  ceres::Problem::Options popt;
  popt.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(popt);
  ceres::HuberLoss huber_mono(opt.huber_px);
  ceres::HuberLoss huber_stereo(opt.huber_px * std::sqrt(kChi2Stereo / kChi2Mono));
  for (size_t i = 0; i < obs.size(); ++i) {
    double* pose = pose_of(obs[i].kf);
    double* pt = point_of(obs[i].point);
    if (obs_ur[i] >= 0) {
      auto* c = new ceres::AutoDiffCostFunction<StereoReprojectionCost, 3, 6, 3>(
          new StereoReprojectionCost(cam, obs_u[i], obs_v[i], obs_ur[i], obs_w[i]));
      problem.AddResidualBlock(c, &huber_stereo, pose, pt);
    } else {
      auto* c = new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 6, 3>(
          new ReprojectionCost(cam, obs_u[i], obs_v[i], -1, obs_w[i]));
      problem.AddResidualBlock(c, &huber_mono, pose, pt);
    }
  }
  for (KeyFrame* k : fixed) {
    if (problem.HasParameterBlock(pose_of(k))) problem.SetParameterBlockConstant(pose_of(k));
  }
  for (KeyFrame* k : local) {
    if (k->fixed && problem.HasParameterBlock(pose_of(k))) problem.SetParameterBlockConstant(pose_of(k));
  }
  ceres::Solver::Options sopt;
  sopt.linear_solver_type = ceres::DENSE_SCHUR;
  sopt.max_num_iterations = opt.iterations;
  sopt.num_threads = 1;
  sopt.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(sopt, &problem, &summary);
  res.initial_cost = summary.initial_cost;
  res.final_cost = summary.final_cost;

  std::lock_guard<std::mutex> lock(*map_mutex);
  for (KeyFrame* k : local) {
    if (!k->bad && !k->fixed) k->T_c_w = ParamsToPose(pose_of(k));
  }
  for (MapPoint* p : points) {
    if (p->bad) continue;
    const double* q = point_of(p);
    p->p_w = Eigen::Vector3d(q[0], q[1], q[2]);
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

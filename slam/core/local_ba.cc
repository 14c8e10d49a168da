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

// The reprojection residual of ReprojectionCost / StereoReprojectionCost (same values: the same
// angle-axis rotation and clamp of the depth), with its Jacobians written out instead of
// automatic differentiation, which was most of local BA's evaluation time:
//   p = R(a) P + t,  d p / d t = I,  d p / d P = R,  d p / d a = -[R P]x J_l(a),
// J_l the left Jacobian of SO(3). Rows: u, v (and the right image's u for `Rows` = 3).
template <int Rows>
class AnalyticReprojectionCost : public ceres::SizedCostFunction<Rows, 6, 3> {
 public:
  AnalyticReprojectionCost(const StereoCamera& cam, double u, double v, double ur, double w)
      : fx_(cam.fx), fy_(cam.fy), cx_(cam.cx), cy_(cam.cy), bf_(cam.bf), u_(u), v_(v), ur_(ur), w_(w) {}

  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override {
    const double* a = params[0];
    const double* P = params[1];
    double RP[3];
    ceres::AngleAxisRotatePoint(a, P, RP);
    double p[3] = {RP[0] + a[3], RP[1] + a[4], RP[2] + a[5]};
    const bool clamped = p[2] < 1e-4;
    if (clamped) p[2] = 1e-4;
    const double inv_z = 1.0 / p[2];
    const double u = fx_ * p[0] * inv_z + cx_;
    const double v = fy_ * p[1] * inv_z + cy_;
    residuals[0] = (u - u_) * w_;
    residuals[1] = (v - v_) * w_;
    if (Rows == 3) residuals[2] = (u - bf_ * inv_z - ur_) * w_;
    if (jacobians == nullptr || (jacobians[0] == nullptr && jacobians[1] == nullptr)) return true;

    // d(residual) / d p, weighted.
    Eigen::Matrix<double, Rows, 3> Jp = Eigen::Matrix<double, Rows, 3>::Zero();
    const double inv_z2 = inv_z * inv_z;
    Jp(0, 0) = fx_ * inv_z;
    Jp(0, 2) = -fx_ * p[0] * inv_z2;
    Jp(1, 1) = fy_ * inv_z;
    Jp(1, 2) = -fy_ * p[1] * inv_z2;
    if (Rows == 3) {
      Jp(Rows - 1, 0) = fx_ * inv_z;
      Jp(Rows - 1, 2) = (bf_ - fx_ * p[0]) * inv_z2;
    }
    if (clamped) Jp.col(2).setZero();
    Jp *= w_;
    Eigen::Matrix3d R;
    ceres::AngleAxisToRotationMatrix(a, ceres::ColumnMajorAdapter3x3(R.data()));
    if (jacobians[0] != nullptr) {
      const Eigen::Vector3d aa(a[0], a[1], a[2]);
      const double theta2 = aa.squaredNorm();
      const Eigen::Matrix3d A = Skew(aa);
      Eigen::Matrix3d Jl = Eigen::Matrix3d::Identity();
      if (theta2 > 1e-16) {
        const double theta = std::sqrt(theta2);
        Jl += (1 - std::cos(theta)) / theta2 * A + (theta - std::sin(theta)) / (theta2 * theta) * A * A;
      } else {
        Jl += 0.5 * A + A * A / 6.0;
      }
      Eigen::Matrix<double, 3, 6> dp;
      dp.leftCols<3>() = -Skew(Eigen::Vector3d(RP[0], RP[1], RP[2])) * Jl;
      dp.rightCols<3>() = Eigen::Matrix3d::Identity();
      Eigen::Map<Eigen::Matrix<double, Rows, 6, Eigen::RowMajor>> J_pose(jacobians[0]);
      J_pose = Jp * dp;
    }
    if (jacobians[1] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Rows, 3, Eigen::RowMajor>> J_point(jacobians[1]);
      J_point = Jp * R;
    }
    return true;
  }

 private:
  static Eigen::Matrix3d Skew(const Eigen::Vector3d& x) {
    Eigen::Matrix3d S;
    S << 0, -x.z(), x.y(), x.z(), 0, -x.x(), -x.y(), x.x(), 0;
    return S;
  }
  double fx_, fy_, cx_, cy_, bf_, u_, v_, ur_, w_;
};

ceres::CostFunction* MakeBaReprojectionCost(const StereoCamera& cam, double u, double v, double ur, double w) {
  if (ur >= 0) return new AnalyticReprojectionCost<3>(cam, u, v, ur, w);
  return new AnalyticReprojectionCost<2>(cam, u, v, -1, w);
}

namespace {

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
    problem.AddResidualBlock(MakeBaReprojectionCost(cam, obs_u[i], obs_v[i], obs_ur[i], obs_w[i]),
                             obs_ur[i] >= 0 ? &huber_stereo : &huber_mono, pose, pt);
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

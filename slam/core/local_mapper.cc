#include "slam/core/local_mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "slam/core/map.h"
#include "slam/core/reprojection_error.h"

namespace viqu::slam {
namespace {

// Triangulation and fusion use the strict descriptor thresholds (MatcherOptions defaults).
MatcherOptions MapperMatcherOptions(const SlamSettings& s) {
  MatcherOptions m;
  m.max_hamming = s.tracking.max_hamming;
  return m;
}

// Linear triangulation (DLT) of one correspondence from two projection matrices [R|t] in
// normalised coordinates.
bool Triangulate(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, const Eigen::Isometry3d& T1,
                 const Eigen::Isometry3d& T2, Eigen::Vector3d* p) {
  Eigen::Matrix4d A;
  const Eigen::Matrix<double, 3, 4> P1 = T1.matrix().topRows<3>();
  const Eigen::Matrix<double, 3, 4> P2 = T2.matrix().topRows<3>();
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d h = svd.matrixV().col(3);
  if (std::abs(h.w()) < 1e-12) return false;
  *p = h.head<3>() / h.w();
  return p->allFinite();
}

}  // namespace

LocalMapper::LocalMapper(const StereoCamera& cam, const SlamSettings& settings, Map* map)
    : cam_(cam), settings_(settings), map_(map), matcher_(cam, MapperMatcherOptions(settings)) {
  ba_opt_.window = settings.mapping.ba_window;
  ba_opt_.iterations = settings.mapping.ba_iterations;
  ba_opt_.huber_px = settings.mapping.ba_huber_px;
  // Local BA's own weight of near observations' right column (the tracker's camera carries the
  // pose optimiser's).
  cam_.near_right_scale = std::sqrt(settings.stereo.near_right_weight_ba);
  realtime_ = settings.mapping.mode == "realtime";
  if (realtime_) thread_ = std::thread([this] { ThreadLoop(); });
}

LocalMapper::~LocalMapper() {
  if (thread_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      stop_ = true;
    }
    queue_cv_.notify_all();
    thread_.join();
  }
}

void LocalMapper::Insert(KeyFrame* kf) {
  if (!realtime_) {
    Process(kf);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_back(kf);
  }
  queue_cv_.notify_one();
}

void LocalMapper::WaitIdle() {
  if (!realtime_) return;
  std::unique_lock<std::mutex> lock(queue_mutex_);
  idle_cv_.wait(lock, [this] { return queue_.empty() && !busy_; });
}

bool LocalMapper::PinnedIfIdle(std::vector<const KeyFrame*>* keyframes, std::vector<const MapPoint*>* points) const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  if (busy_ || !queue_.empty()) return false;
  keyframes->insert(keyframes->end(), queue_.begin(), queue_.end());
  points->insert(points->end(), recent_.begin(), recent_.end());
  return true;
}

size_t LocalMapper::Queued() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return queue_.size() + (busy_ ? 1 : 0);
}

void LocalMapper::AddRecentPoints(const std::vector<MapPoint*>& points) {
  recent_.insert(recent_.end(), points.begin(), points.end());
}

void LocalMapper::ThreadLoop() {
  while (true) {
    KeyFrame* kf = nullptr;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      queue_cv_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stop requested and nothing left
      kf = queue_.front();
      queue_.pop_front();
      busy_ = true;
    }
    Process(kf);
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      busy_ = false;
    }
    idle_cv_.notify_all();
  }
}

void LocalMapper::Process(KeyFrame* kf) {
  {
    std::lock_guard<std::mutex> lock(map_->mutex);
    LinkObservations(kf);
    CullRecentPoints(kf);
    TriangulateNewPoints(kf);
    FuseWithNeighbours(kf);
  }
  const auto t0 = std::chrono::steady_clock::now();
  LocalBundleAdjustment(cam_, ba_opt_, kf, &map_->mutex);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::lock_guard<std::mutex> lock(map_->mutex);
  ba_ms_.push_back(ms);
  CullKeyFrames(kf);
}

void LocalMapper::LinkObservations(KeyFrame* kf) {
  for (size_t i = 0; i < kf->points.size(); ++i) {
    MapPoint* p = kf->points[i];
    if (!p) continue;
    if (!p->Matchable()) {
      kf->points[i] = nullptr;
      continue;
    }
    auto it = p->observations.find(kf);
    if (it == p->observations.end()) {
      Map::AddObservation(p, kf, static_cast<int>(i));
      p->UpdateFromObservations();
    } else if (it->second != static_cast<int>(i)) {
      kf->points[i] = nullptr;  // the point is already tied to another feature of this keyframe
    }
  }
  kf->UpdateConnections(settings_.mapping.covisibility_min);
}

void LocalMapper::CullRecentPoints(KeyFrame* kf) {
  for (auto it = recent_.begin(); it != recent_.end();) {
    MapPoint* p = *it;
    const int64_t age = kf->id - p->first_keyframe_id;
    if (!p->Matchable()) {
      // A retired point is no longer searched for, so its found ratio says nothing now.
      it = recent_.erase(it);
    } else if (p->FoundRatio() < settings_.mapping.culling_found_ratio) {
      Map::ErasePoint(p);
      it = recent_.erase(it);
    } else if (age >= 2 && p->ObservationWeight() <= 2) {
      // ORB-SLAM's recent-point test: two keyframes after its creation a point must be seen by
      // more than 2 (stereo counts twice) and is no longer watched from the third on.
      Map::ErasePoint(p);
      it = recent_.erase(it);
    } else if (age >= 3) {
      it = recent_.erase(it);
    } else {
      ++it;
    }
  }
}

int LocalMapper::TriangulateNewPoints(KeyFrame* kf) {
  const FrameFeatures& f1 = *kf->features;
  const Eigen::Isometry3d T1 = kf->T_c_w;
  const Eigen::Vector3d c1 = kf->Center();
  const double cos_min_parallax = std::cos(settings_.mapping.min_parallax_deg * M_PI / 180.0);
  const double baseline = cam_.bf / cam_.fx;
  int created = 0;
  std::vector<MapPoint*> created_points;
  for (KeyFrame* kf2 : kf->BestCovisible(settings_.mapping.triangulation_neighbours)) {
    const Eigen::Vector3d c2 = kf2->Center();
    if ((c2 - c1).norm() < baseline) continue;  // the stereo pair already sees more parallax
    const FrameFeatures& f2 = *kf2->features;
    const Eigen::Isometry3d T2 = kf2->T_c_w;
    for (const auto& [i1, i2] : matcher_.SearchForTriangulation(*kf, *kf2)) {
      if (kf->points[i1] || kf2->points[i2]) continue;
      const FeaturePoint& k1 = f1.keypoints[i1];
      const FeaturePoint& k2 = f2.keypoints[i2];
      const Eigen::Vector3d x1((k1.pt.x - cam_.cx) / cam_.fx, (k1.pt.y - cam_.cy) / cam_.fy, 1);
      const Eigen::Vector3d x2((k2.pt.x - cam_.cx) / cam_.fx, (k2.pt.y - cam_.cy) / cam_.fy, 1);
      const Eigen::Vector3d r1 = T1.rotation().transpose() * x1;
      const Eigen::Vector3d r2 = T2.rotation().transpose() * x2;
      const double cos_rays = r1.dot(r2) / (r1.norm() * r2.norm());
      // Parallax the stereo pair would give, when the feature has stereo depth.
      const double cos_stereo1 = f1.depth[i1] > 0 ? std::cos(2 * std::atan2(baseline / 2, f1.depth[i1])) : 2.0;
      const double cos_stereo2 = f2.depth[i2] > 0 ? std::cos(2 * std::atan2(baseline / 2, f2.depth[i2])) : 2.0;
      const double cos_stereo = std::min(cos_stereo1, cos_stereo2);
      Eigen::Vector3d p;
      if (cos_rays < cos_stereo && cos_rays > 0 && cos_rays < cos_min_parallax) {
        if (!Triangulate(x1, x2, T1, T2, &p)) continue;
      } else if (cos_stereo1 < cos_stereo2) {
        p = kf->T_c_w.inverse() * f1.Unproject(cam_, i1);
      } else if (cos_stereo2 < cos_stereo1) {
        p = kf2->T_c_w.inverse() * f2.Unproject(cam_, i2);
      } else {
        continue;  // too little parallax and no stereo depth
      }
      const Eigen::Vector3d p1 = T1 * p, p2 = T2 * p;
      if (!IsInlierObservation(cam_, f1, i1, p1) || !IsInlierObservation(cam_, f2, i2, p2)) continue;
      // Scale consistency: distance ratio against the levels' scale ratio.
      const double d1 = (p - c1).norm(), d2 = (p - c2).norm();
      if (d1 <= 0 || d2 <= 0) continue;
      const double ratio_dist = d2 / d1;
      const double ratio_octave = f1.level_scale[k1.octave] / f2.level_scale[k2.octave];
      const double factor = 1.5 * (f1.level_scale.size() > 1 ? f1.level_scale[1] : 1.2);
      if (ratio_dist * factor < ratio_octave || ratio_dist > ratio_octave * factor) continue;
      MapPoint* mp = map_->AddPoint(p, kf);
      mp->object = f1.object.empty() ? 0 : f1.object[i1];
      Map::AddObservation(mp, kf, i1);
      Map::AddObservation(mp, kf2, i2);
      mp->UpdateFromObservations();
      created_points.push_back(mp);
      ++created;
    }
  }
  AddRecentPoints(created_points);
  return created;
}

void LocalMapper::FuseWithNeighbours(KeyFrame* kf) {
  std::vector<KeyFrame*> targets = kf->BestCovisible(static_cast<size_t>(settings_.mapping.triangulation_neighbours));
  std::set<KeyFrame*> seen(targets.begin(), targets.end());
  seen.insert(kf);
  const size_t first = targets.size();
  for (size_t i = 0; i < first; ++i) {
    for (KeyFrame* n : targets[i]->BestCovisible(5)) {  // ORB-SLAM's second ring: 5 neighbours each
      if (seen.insert(n).second) targets.push_back(n);
    }
  }
  std::vector<MapPoint*> own;
  for (MapPoint* p : kf->points) {
    if (p && p->Matchable()) own.push_back(p);
  }
  for (KeyFrame* t : targets) matcher_.Fuse(t, own, 3.0);
  std::vector<MapPoint*> theirs;
  std::set<MapPoint*> theirs_set;
  for (KeyFrame* t : targets) {
    for (MapPoint* p : t->points) {
      if (p && p->Matchable() && theirs_set.insert(p).second) theirs.push_back(p);
    }
  }
  std::sort(theirs.begin(), theirs.end(), [](const MapPoint* a, const MapPoint* b) { return a->id < b->id; });
  matcher_.Fuse(kf, theirs, 3.0);
  for (MapPoint* p : kf->points) {
    if (p && !p->bad) p->UpdateFromObservations();
  }
  kf->UpdateConnections(settings_.mapping.covisibility_min);
}

void LocalMapper::CullKeyFrames(KeyFrame* kf) {
  const double ratio = settings_.mapping.redundant_keyframe_ratio;
  for (KeyFrame* n : kf->BestCovisible(static_cast<size_t>(settings_.mapping.ba_window * 2))) {
    if (n->fixed || n->bad || n == kf) continue;
    int good = 0, redundant = 0;
    for (size_t i = 0; i < n->points.size(); ++i) {
      MapPoint* p = n->points[i];
      if (!p || p->bad) continue;
      ++good;
      // ORB-SLAM's redundancy: a point seen by at least 3 other keyframes at the same or a finer
      // scale (one level of slack).
      if (p->ObservationWeight() <= 3) continue;
      const int level = n->features->keypoints[i].octave;
      int others = 0;
      for (const auto& [o, idx] : p->observations) {
        if (o == n || o->bad) continue;
        if (o->features->keypoints[idx].octave <= level + 1) ++others;
        if (others >= 3) break;
      }
      if (others >= 3) ++redundant;
    }
    if (good > 0 && redundant > ratio * good) map_->EraseKeyFrame(n, settings_.mapping.covisibility_min);
  }
}

}  // namespace viqu::slam

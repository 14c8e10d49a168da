#include "slam/core/matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slam/core/map.h"
#include "slam/core/reprojection_error.h"

namespace viqu::slam {
namespace {

struct Best {
  int idx = -1;
  int dist = std::numeric_limits<int>::max();
  int second = std::numeric_limits<int>::max();
  int best_level = -1, second_level = -1;
  void Offer(int i, int d, int level) {
    if (d < dist) {
      second = dist;
      second_level = best_level;
      dist = d;
      idx = i;
      best_level = level;
    } else if (d < second) {
      second = d;
      second_level = level;
    }
  }
};

// How a map point would appear in an image taken from pose T_c_w (camera centre `center`).
struct View {
  Eigen::Vector3d p_c;   // point in the camera frame
  Eigen::Vector2d uv;    // pixel
  int level = 0;         // predicted pyramid level
  double view_cos = 1;   // cosine between the viewing ray and the point's mean viewing direction
};

// False when the point is behind the camera, outside the image, outside its scale-invariance
// distance range (with a 20% margin) or seen more than 60 degrees off its mean viewing direction.
bool PredictView(const StereoCamera& cam, const MapPoint& p, const Eigen::Isometry3d& T_c_w,
                 const Eigen::Vector3d& center, const FrameFeatures& f, View* v) {
  v->p_c = T_c_w * p.p_w;
  if (v->p_c.z() <= 0) return false;
  v->uv = cam.Project(v->p_c);
  if (!cam.InImage(v->uv.x(), v->uv.y())) return false;
  const Eigen::Vector3d ray = p.p_w - center;
  const double dist = ray.norm();
  // ORB-SLAM's view gates: within the scale range the point's pyramid level allows (20% slack)
  // and within 60 degrees of its mean viewing direction.
  if (dist < 0.8 * p.min_distance || dist > 1.2 * p.max_distance) return false;
  if (ray.dot(p.normal) < 0.5 * dist) return false;
  v->view_cos = ray.dot(p.normal) / dist;
  v->level = p.PredictLevel(dist, f);
  return true;
}

// Whether `keep` may take over the observations of `drop`: it must lie in front of every
// keyframe that observes `drop` and project within `radius` (pixels of the feature's level) of
// that keyframe's feature, as the fusion search itself asks of the keyframe it searches. Without
// this, on a repetitive texture the search in a keyframe that has no stereo depth for the
// feature matches a different point on the same ray, and the merge hands the other keyframes'
// observations a point a metre away, even behind their cameras, which drags local BA.
bool MergeIsConsistent(const StereoCamera& cam, const MapPoint& keep, const MapPoint& drop, double radius) {
  for (const auto& [k, idx] : drop.observations) {
    if (k->bad || keep.observations.count(k)) continue;
    const Eigen::Vector3d pc = k->T_c_w * keep.p_w;
    if (pc.z() <= 0) return false;
    const FeaturePoint& kp = k->features->keypoints[idx];
    const Eigen::Vector2d uv = cam.Project(pc);
    if ((uv - Eigen::Vector2d(kp.pt.x, kp.pt.y)).norm() > radius * k->features->level_scale[kp.octave]) return false;
  }
  return true;
}

}  // namespace

int Matcher::SearchByProjection(const Frame& last, double radius, Frame* cur) const {
  const FrameFeatures& f = *cur->features;
  int matches = 0;
  std::vector<int> cand;
  for (size_t i = 0; i < last.size(); ++i) {
    MapPoint* p = last.points[i];
    if (!p || !p->Matchable() || last.outlier[i]) continue;
    const Eigen::Vector3d pc = cur->T_c_w * p->p_w;
    if (pc.z() <= 0) continue;
    const Eigen::Vector2d uv = cam_.Project(pc);
    if (!cam_.InImage(uv.x(), uv.y())) continue;
    const int level = last.features->keypoints[i].octave;
    const double r = radius * f.level_scale[level];
    const int nl = static_cast<int>(f.level_scale.size());
    f.InArea(uv.x(), uv.y(), r, std::max(0, level - 1), std::min(nl - 1, level + 1), &cand);
    Best b;
    const double ur = cam_.ProjectRight(pc);
    for (int j : cand) {
      if (cur->points[j] && !cur->points[j]->bad) continue;
      if (f.u_right[j] >= 0 && std::abs(ur - f.u_right[j]) > r) continue;
      b.Offer(j, DescriptorDistance(p->descriptor.data(), f.descriptors.ptr<uint8_t>(j)), f.keypoints[j].octave);
    }
    if (b.idx >= 0 && b.dist <= opt_.max_hamming) {
      cur->points[b.idx] = p;
      cur->outlier[b.idx] = false;
      ++matches;
    }
  }
  return matches;
}

int Matcher::SearchLocalPoints(const std::vector<MapPoint*>& points, double radius, Frame* cur, bool count_visible) const {
  const FrameFeatures& f = *cur->features;
  const Eigen::Vector3d center = cur->Center();
  // The frame's matched points, sorted for binary search (a tree of them cost a node allocation
  // each and a pointer chase per look-up).
  std::vector<const MapPoint*> already;
  for (size_t i = 0; i < cur->size(); ++i) {
    if (cur->points[i] && !cur->outlier[i]) already.push_back(cur->points[i]);
  }
  std::sort(already.begin(), already.end());
  int matches = 0;
  std::vector<int> cand;
  for (MapPoint* p : points) {
    if (!p->Matchable() || std::binary_search(already.begin(), already.end(), p)) continue;
    View v;
    if (!PredictView(cam_, *p, cur->T_c_w, center, f, &v)) continue;
    if (count_visible) ++p->visible;
    const Eigen::Vector3d& pc = v.p_c;
    const Eigen::Vector2d& uv = v.uv;
    const int level = v.level;
    // Wider windows when the view is oblique.
    const double r = radius * (v.view_cos > 0.998 ? 1.0 : 1.5) * f.level_scale[level];  // ORB-SLAM's: beyond 3.6 deg
    f.InArea(uv.x(), uv.y(), r, level - 1, level, &cand);
    Best b;
    const double ur = cam_.ProjectRight(pc);
    for (int j : cand) {
      if (cur->points[j] && !cur->points[j]->bad && !cur->outlier[j] && cur->points[j]->observations.size() > 0) continue;
      if (f.u_right[j] >= 0 && std::abs(ur - f.u_right[j]) > r) continue;
      b.Offer(j, DescriptorDistance(p->descriptor.data(), f.descriptors.ptr<uint8_t>(j)), f.keypoints[j].octave);
    }
    if (b.idx < 0 || b.dist > opt_.max_hamming) continue;
    if (b.best_level == b.second_level && b.dist > opt_.ratio * b.second) continue;
    cur->points[b.idx] = p;
    cur->outlier[b.idx] = false;
    ++matches;
  }
  return matches;
}

int Matcher::SearchByDescriptor(const KeyFrame& kf, Frame* cur) const {
  const FrameFeatures& f = *cur->features;
  std::vector<int> best_for_feature(f.size(), std::numeric_limits<int>::max());
  std::vector<MapPoint*> chosen(f.size(), nullptr);
  for (size_t i = 0; i < kf.points.size(); ++i) {
    MapPoint* p = kf.points[i];
    if (!p || !p->Matchable()) continue;
    const uint8_t* d = kf.features->descriptors.ptr<uint8_t>(static_cast<int>(i));
    Best b;
    for (size_t j = 0; j < f.size(); ++j) {
      b.Offer(static_cast<int>(j), DescriptorDistance(d, f.descriptors.ptr<uint8_t>(static_cast<int>(j))),
              f.keypoints[j].octave);
    }
    if (b.idx < 0 || b.dist > opt_.strict_hamming || b.dist > opt_.bf_ratio * b.second) continue;
    if (b.dist < best_for_feature[b.idx]) {
      best_for_feature[b.idx] = b.dist;
      chosen[b.idx] = p;
    }
  }
  int matches = 0;
  for (size_t j = 0; j < f.size(); ++j) {
    if (!chosen[j]) continue;
    cur->points[j] = chosen[j];
    cur->outlier[j] = false;
    ++matches;
  }
  return matches;
}

std::vector<std::pair<int, int>> Matcher::SearchForTriangulation(const KeyFrame& kf1, const KeyFrame& kf2) const {
  const FrameFeatures& f1 = *kf1.features;
  const FrameFeatures& f2 = *kf2.features;
  // Fundamental matrix F12 such that x1^T F12 x2 = 0.
  const Eigen::Isometry3d T12 = kf1.T_c_w * kf2.T_c_w.inverse();
  const Eigen::Matrix3d R12 = T12.rotation();
  const Eigen::Vector3d t12 = T12.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t12.z(), t12.y(), t12.z(), 0, -t12.x(), -t12.y(), t12.x(), 0;
  Eigen::Matrix3d K;
  K << cam_.fx, 0, cam_.cx, 0, cam_.fy, cam_.cy, 0, 0, 1;
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Matrix3d F12 = Kinv.transpose() * tx * R12 * Kinv;
  // Epipole of camera 1 in image 2: features near it give no parallax.
  const Eigen::Vector3d c1_in_2 = kf2.T_c_w * kf1.Center();
  const bool epipole_valid = c1_in_2.z() > 1e-6;
  const Eigen::Vector2d ep = epipole_valid ? cam_.Project(c1_in_2) : Eigen::Vector2d(-1e9, -1e9);

  std::vector<int> free2;
  for (size_t j = 0; j < f2.size(); ++j) {
    if (!kf2.points[j] || kf2.points[j]->bad) free2.push_back(static_cast<int>(j));
  }
  std::vector<int> best_for2(f2.size(), std::numeric_limits<int>::max());
  std::vector<int> match_of2(f2.size(), -1);
  for (size_t i = 0; i < f1.size(); ++i) {
    if (kf1.points[i] && !kf1.points[i]->bad) continue;
    const FeaturePoint& k1 = f1.keypoints[i];
    // The epipolar line in image 2 of feature i: l2 = F12^T x1.
    const Eigen::Vector3d l2 = F12.transpose() * Eigen::Vector3d(k1.pt.x, k1.pt.y, 1);
    const double ln = std::sqrt(l2.x() * l2.x() + l2.y() * l2.y());
    if (ln < 1e-12) continue;
    const uint8_t* d1 = f1.descriptors.ptr<uint8_t>(static_cast<int>(i));
    Best b;
    for (int j : free2) {
      const FeaturePoint& k2 = f2.keypoints[j];
      if (std::abs(k2.octave - k1.octave) > 1) continue;
      const double dist_line = std::abs(l2.dot(Eigen::Vector3d(k2.pt.x, k2.pt.y, 1))) / ln;
      if (dist_line * dist_line > 3.84 * f2.level_sigma2[k2.octave]) continue;
      const int d = DescriptorDistance(d1, f2.descriptors.ptr<uint8_t>(j));
      if (d > opt_.strict_hamming) continue;
      // Without stereo depth, a feature next to the epipole could be at any depth.
      if (f1.depth[i] < 0 && f2.depth[j] < 0) {
        const double de = (Eigen::Vector2d(k2.pt.x, k2.pt.y) - ep).norm();
        if (de < 10 * f2.level_scale[k2.octave]) continue;  // ORB-SLAM's 10 px (times the level's scale)
      }
      b.Offer(j, d, k2.octave);
    }
    if (b.idx < 0 || b.dist > opt_.bf_ratio * b.second) continue;
    if (b.dist < best_for2[b.idx]) {
      best_for2[b.idx] = b.dist;
      match_of2[b.idx] = static_cast<int>(i);
    }
  }
  std::vector<std::pair<int, int>> out;
  for (size_t j = 0; j < f2.size(); ++j) {
    if (match_of2[j] >= 0) out.emplace_back(match_of2[j], static_cast<int>(j));
  }
  return out;
}

int Matcher::Fuse(KeyFrame* kf, const std::vector<MapPoint*>& points, double radius) const {
  const FrameFeatures& f = *kf->features;
  const Eigen::Vector3d center = kf->Center();
  int fused = 0;
  std::vector<int> cand;
  for (MapPoint* p : points) {
    if (!p || !p->Matchable() || p->observations.count(kf)) continue;
    View v;
    if (!PredictView(cam_, *p, kf->T_c_w, center, f, &v)) continue;
    const Eigen::Vector3d& pc = v.p_c;
    const Eigen::Vector2d& uv = v.uv;
    const int level = v.level;
    const double r = radius * f.level_scale[level];
    Best b;
    f.InArea(uv.x(), uv.y(), r, level - 1, level, &cand);
    for (int j : cand) {
      if (!IsInlierObservation(cam_, f, j, pc)) continue;
      b.Offer(j, DescriptorDistance(p->descriptor.data(), f.descriptors.ptr<uint8_t>(j)), f.keypoints[j].octave);
    }
    if (b.idx < 0 || b.dist > opt_.strict_hamming) continue;
    MapPoint* other = kf->points[b.idx];
    if (other && other->retired) continue;  // the feature already holds a point of the past
    if (other && !other->bad) {
      MapPoint* keep = other->observations.size() > p->observations.size() ? other : p;
      MapPoint* drop = keep == other ? p : other;
      if (!MergeIsConsistent(cam_, *keep, *drop, radius)) continue;
      Map::Replace(drop, keep);
    } else {
      Map::AddObservation(p, kf, b.idx);
    }
    ++fused;
  }
  return fused;
}

}  // namespace viqu::slam

#include "slam/core/map.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <unordered_set>

#include "slam/features/hamming.h"

namespace viqu::slam {

int DescriptorDistance(const uint8_t* a, const uint8_t* b) { return HammingDistance(a, b, 32); }

int DescriptorDistance(const cv::Mat& a, const cv::Mat& b) { return DescriptorDistance(a.ptr<uint8_t>(), b.ptr<uint8_t>()); }

void MapPoint::SetDescriptor(const cv::Mat& descriptors, int row) {
  if (descriptors.type() != CV_8U || descriptors.cols != static_cast<int>(descriptor.size())) {
    throw std::logic_error("MapPoint::SetDescriptor: descriptors must be CV_8U with 32 bytes a row");
  }
  const uint8_t* src = descriptors.ptr<uint8_t>(row);
  std::copy(src, src + descriptor.size(), descriptor.begin());
}

void MapPoint::UpdateFromObservations() {
  if (observations.empty()) return;
  // Descriptor: the one with the least median distance to the others.
  std::vector<const uint8_t*> descs;
  descs.reserve(observations.size());
  for (const auto& [kf, idx] : observations) descs.push_back(kf->features->descriptors.ptr<uint8_t>(idx));
  const size_t n = descs.size();
  int best = 0, best_median = std::numeric_limits<int>::max();
  for (size_t i = 0; i < n; ++i) {
    std::vector<int> d;
    d.reserve(n);
    for (size_t j = 0; j < n; ++j) d.push_back(i == j ? 0 : DescriptorDistance(descs[i], descs[j]));
    std::nth_element(d.begin(), d.begin() + (n - 1) / 2, d.end());
    const int med = d[(n - 1) / 2];
    if (med < best_median) {
      best_median = med;
      best = static_cast<int>(i);
    }
  }
  auto it = observations.begin();
  std::advance(it, best);
  SetDescriptor(it->first->features->descriptors, it->second);

  Eigen::Vector3d nsum = Eigen::Vector3d::Zero();
  for (const auto& [kf, idx] : observations) nsum += (p_w - kf->Center()).normalized();
  normal = nsum.normalized();
  const KeyFrame* ref = reference && !reference->bad && observations.count(reference) ? reference : observations.begin()->first;
  const int ref_idx = observations.at(const_cast<KeyFrame*>(ref));
  const double dist = (p_w - ref->Center()).norm();
  const FrameFeatures& f = *ref->features;
  const int level = f.keypoints[ref_idx].octave;
  max_distance = dist * f.level_scale[level];
  min_distance = max_distance / f.level_scale.back();
}

int MapPoint::PredictLevel(double dist, const FrameFeatures& f) const {
  if (dist <= 0) return 0;
  const double ratio = max_distance / dist;
  const double log_scale = std::log(f.level_scale.size() > 1 ? f.level_scale[1] : 1.2);
  const int level = static_cast<int>(std::ceil(std::log(ratio) / log_scale));
  return std::clamp(level, 0, static_cast<int>(f.level_scale.size()) - 1);
}

int MapPoint::ObservationWeight() const {
  int w = 0;
  for (const auto& [kf, idx] : observations) w += kf->features->u_right[idx] >= 0 ? 2 : 1;
  return w;
}

KeyFrame::KeyFrame(int64_t id, const Frame& frame)
    : id(id), t_ns(frame.t_ns), features(frame.features), points(frame.points), T_c_w(frame.T_c_w) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (frame.outlier[i] || (points[i] && points[i]->bad)) points[i] = nullptr;
  }
}

std::vector<KeyFrame*> KeyFrame::BestCovisible(size_t n) const {
  std::vector<std::pair<int, KeyFrame*>> v;
  for (const auto& [kf, w] : covisible) {
    if (!kf->bad) v.emplace_back(w, kf);
  }
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->id < b.second->id;
  });
  std::vector<KeyFrame*> out;
  for (size_t i = 0; i < v.size() && i < n; ++i) out.push_back(v[i].second);
  return out;
}

void KeyFrame::UpdateConnections(int min_shared) {
  KeyFrameMap<int> counts;
  for (MapPoint* p : points) {
    if (!p || p->bad) continue;
    for (const auto& [kf, idx] : p->observations) {
      if (kf != this && !kf->bad) ++counts[kf];
    }
  }
  for (auto& [kf, w] : covisible) kf->covisible.erase(this);
  covisible.clear();
  KeyFrame* best = nullptr;
  int best_w = 0;
  for (const auto& [kf, w] : counts) {
    if (w > best_w) {
      best_w = w;
      best = kf;
    }
    if (w >= min_shared) covisible[kf] = w;
  }
  if (covisible.empty() && best) covisible[best] = best_w;
  for (const auto& [kf, w] : covisible) kf->covisible[this] = w;
}

int KeyFrame::TrackedPoints(int min_observations) const {
  int n = 0;
  for (MapPoint* p : points) {
    if (p && !p->bad && p->ObservationWeight() >= min_observations) ++n;
  }
  return n;
}

KeyFrame* Map::AddKeyFrame(const Frame& frame) {
  keyframes_.push_back(std::make_unique<KeyFrame>(next_keyframe_id_++, frame));
  return keyframes_.back().get();
}

MapPoint* Map::AddPoint(const Eigen::Vector3d& p_w, KeyFrame* ref) {
  points_.push_back(std::make_unique<MapPoint>(next_point_id_++, p_w, ref));
  points_.back()->first_keyframe_id = ref->id;
  return points_.back().get();
}

void Map::AddObservation(MapPoint* p, KeyFrame* kf, int idx) {
  p->observations[kf] = idx;
  kf->points[idx] = p;
}

void Map::EraseObservation(MapPoint* p, KeyFrame* kf) {
  auto it = p->observations.find(kf);
  if (it == p->observations.end()) return;
  if (kf->points[it->second] == p) kf->points[it->second] = nullptr;
  p->observations.erase(it);
  if (p->observations.empty()) p->bad = true;
}

int Map::RetireObjectPoints(uint16_t object, int64_t moving_from_ns, int* retired) {
  int erased = 0, kept = 0;
  std::vector<KeyFrame*> late;
  for (const auto& p : points_) {
    if (!p->Matchable() || p->object != object || object == 0) continue;
    late.clear();
    for (const auto& [kf, idx] : p->observations) {
      if (kf->t_ns >= moving_from_ns) late.push_back(kf);
    }
    for (KeyFrame* kf : late) EraseObservation(p.get(), kf);
    // One keyframe's observation alone ties nothing together: the point would only follow it.
    if (p->observations.size() < 2) {
      if (!p->bad) ErasePoint(p.get());
      ++erased;
      continue;
    }
    p->retired = true;
    p->UpdateFromObservations();
    ++kept;
  }
  if (retired) *retired = kept;
  return erased;
}

void Map::ErasePoint(MapPoint* p) {
  p->bad = true;
  for (const auto& [kf, idx] : p->observations) {
    if (kf->points[idx] == p) kf->points[idx] = nullptr;
  }
  p->observations.clear();
}

void Map::Replace(MapPoint* a, MapPoint* b) {
  if (a == b || a->bad || b->bad) return;
  for (const auto& [kf, idx] : a->observations) {
    if (b->observations.count(kf)) {
      kf->points[idx] = nullptr;
    } else {
      kf->points[idx] = b;
      b->observations[kf] = idx;
    }
  }
  b->visible += a->visible;
  b->found += a->found;
  a->observations.clear();
  a->bad = true;
}

void Map::EraseKeyFrame(KeyFrame* kf, int min_shared) {
  if (kf->fixed || kf->bad) return;
  std::vector<KeyFrame*> neighbours;
  for (const auto& [n, w] : kf->covisible) neighbours.push_back(n);
  for (KeyFrame* n : neighbours) n->covisible.erase(kf);
  kf->covisible.clear();
  kf->bad = true;
  for (size_t i = 0; i < kf->points.size(); ++i) {
    if (MapPoint* p = kf->points[i]) EraseObservation(p, kf);
  }
  for (KeyFrame* n : neighbours) n->UpdateConnections(min_shared);
}

size_t Map::Reclaim(const std::vector<const KeyFrame*>& pinned_keyframes, const std::vector<const MapPoint*>& pinned_points) {
  const std::unordered_set<const KeyFrame*> kf_pins(pinned_keyframes.begin(), pinned_keyframes.end());
  const std::unordered_set<const MapPoint*> point_pins(pinned_points.begin(), pinned_points.end());
  std::unordered_set<const KeyFrame*> freed_kfs;
  for (const auto& kf : keyframes_) {
    if (kf->bad && !kf_pins.count(kf.get())) freed_kfs.insert(kf.get());
  }
  // Nothing that stays may point at a freed keyframe: a bad keyframe has no observations and is
  // in no good keyframe's covisibility (EraseKeyFrame); only map points' `reference` and kept
  // (pinned) bad keyframes' covisibility can still name it.
  for (const auto& p : points_) {
    if (freed_kfs.count(p->reference)) p->reference = nullptr;
  }
  for (const auto& kf : keyframes_) {
    if (freed_kfs.count(kf.get())) continue;
    for (auto it = kf->covisible.begin(); it != kf->covisible.end();) {
      it = freed_kfs.count(it->first) ? kf->covisible.erase(it) : std::next(it);
    }
  }
  const size_t kfs_before = keyframes_.size(), points_before = points_.size();
  keyframes_.erase(std::remove_if(keyframes_.begin(), keyframes_.end(),
                                  [&](const std::unique_ptr<KeyFrame>& kf) { return freed_kfs.count(kf.get()) > 0; }),
                   keyframes_.end());
  // A bad point has no observations (ErasePoint, Replace, EraseObservation of the last one), so no
  // keyframe holds it.
  points_.erase(std::remove_if(points_.begin(), points_.end(),
                               [&](const std::unique_ptr<MapPoint>& p) { return p->bad && !point_pins.count(p.get()); }),
                points_.end());
  const size_t kfs = kfs_before - keyframes_.size(), points = points_before - points_.size();
  keyframes_freed_ += static_cast<int64_t>(kfs);
  points_freed_ += static_cast<int64_t>(points);
  return kfs + points;
}

namespace {
// A node of std::map<KeyFrame*, int> in libstdc++ (colour, three links, key and value: 40 bytes)
// with glibc malloc's 8-byte header, rounded to its 16-byte granule.
constexpr size_t kTreeNodeBytes = 48;

template <class T>
size_t VectorBytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

size_t FeatureBytes(const FrameFeatures& f) {
  return sizeof(FrameFeatures) + VectorBytes(f.keypoints) + f.descriptors.total() * f.descriptors.elemSize() +
         VectorBytes(f.u_right) + VectorBytes(f.depth) + VectorBytes(f.object) + VectorBytes(f.level_sigma2) +
         VectorBytes(f.level_scale) + VectorBytes(f.grid_start) + VectorBytes(f.grid_index);
}
}  // namespace

size_t Map::HeapBytes() const {
  size_t bytes = VectorBytes(keyframes_) + VectorBytes(points_);
  for (const auto& k : keyframes_) {
    bytes += sizeof(KeyFrame) + VectorBytes(k->points) + k->covisible.size() * kTreeNodeBytes;
    if (k->features) bytes += FeatureBytes(*k->features);
  }
  for (const auto& p : points_) bytes += sizeof(MapPoint) + p->observations.capacity() * sizeof(std::pair<KeyFrame*, int>);
  return bytes;
}

std::vector<KeyFrame*> Map::NearbyKeyFrames(const Eigen::Isometry3d& T_w_c, double radius_m, double max_angle_deg,
                                             const std::set<KeyFrame*>& exclude, size_t max_count) const {
  const Eigen::Vector3d centre = T_w_c.translation(), axis = T_w_c.linear().col(2);
  const double max_d2 = radius_m * radius_m;
  const bool any_direction = max_angle_deg >= 180;  // (a dot product of opposite unit axes may round below -1)
  const double min_cos = std::cos(max_angle_deg * M_PI / 180.0);
  std::vector<std::pair<double, KeyFrame*>> near;
  for (const auto& k : keyframes_) {
    if (k->bad || exclude.count(k.get())) continue;
    const Eigen::Isometry3d T_w_k = k->T_c_w.inverse();
    const double d2 = (T_w_k.translation() - centre).squaredNorm();
    if (d2 > max_d2 || (!any_direction && T_w_k.linear().col(2).dot(axis) < min_cos)) continue;
    near.emplace_back(d2, k.get());
  }
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second->id < b.second->id;
  });
  std::vector<KeyFrame*> out;
  for (size_t i = 0; i < near.size() && i < max_count; ++i) out.push_back(near[i].second);
  return out;
}

int Map::GoodKeyFrames() const {
  return static_cast<int>(std::count_if(keyframes_.begin(), keyframes_.end(), [](const auto& k) { return !k->bad; }));
}

int Map::GoodPoints() const {
  return static_cast<int>(std::count_if(points_.begin(), points_.end(), [](const auto& p) { return !p->bad; }));
}

}  // namespace viqu::slam

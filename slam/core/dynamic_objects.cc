#include "slam/core/dynamic_objects.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace viqu::slam {
namespace {

constexpr int kMaxSnapshotPoints = 256;  // features per object kept for matching over time (bounds
                                         // the quadratic descriptor search; nearest first)

// Whether the pixels `r` px away from (u, v) in the eight directions all carry `id` (pixels off
// the image count as the same id: the image border is not the object's edge).
bool InteriorOf(const cv::Mat& instance_id, const FeaturePoint& kp, uint16_t id, int r) {
  const int u = static_cast<int>(std::lround(kp.pt.x)), v = static_cast<int>(std::lround(kp.pt.y));
  for (int dv = -r; dv <= r; dv += r) {
    for (int du = -r; du <= r; du += r) {
      const int x = u + du, y = v + dv;
      if (x < 0 || y < 0 || x >= instance_id.cols || y >= instance_id.rows) continue;
      if (instance_id.at<uint16_t>(y, x) != id) return false;
    }
  }
  return true;
}

}  // namespace

DynamicMethod DynamicMethodOf(const SlamSettings& s) {
  if (s.mode == "visual") return DynamicMethod::kNone;
  const std::string& m = s.dynamic.method;
  if (m == "semantic") return DynamicMethod::kSemantic;
  if (m == "paper") return DynamicMethod::kPaper;
  if (m == "adaptive") return DynamicMethod::kAdaptive;
  return DynamicMethod::kNone;
}

bool IsMovable(Category c) { return c == Category::kPerson || c == Category::kBox || c == Category::kBall; }

DynamicObjects::DynamicObjects(const SlamSettings& settings, const StereoCamera& cam)
    : settings_(settings.dynamic), method_(DynamicMethodOf(settings)), cam_(cam) {}

std::vector<bool> DynamicObjects::KeepMask(const FrameFeatures& f, const std::vector<SegmentInstance>& instances) {
  // One report per movable instance, in id order (an id listed twice counts once).
  std::map<uint16_t, ObjectReport> by_id;
  for (const SegmentInstance& inst : instances) {
    if (inst.id == 0 || !IsMovable(inst.category) || by_id.count(inst.id)) continue;
    ObjectReport& r = by_id[inst.id];
    r.id = inst.id;
    r.name = inst.name;
    r.category = inst.category;
    const auto it = objects_.find(inst.id);
    r.dynamic = method_ == DynamicMethod::kSemantic || (it != objects_.end() && it->second.dynamic);
  }
  std::vector<bool> keep(f.size(), true);
  for (size_t i = 0; i < f.size(); ++i) {
    const auto it = f.object.empty() ? by_id.end() : by_id.find(f.object[i]);
    if (it == by_id.end()) continue;
    ObjectReport& r = it->second;
    ++r.features;
    if (r.dynamic && method_ != DynamicMethod::kNone) {
      keep[i] = false;
      ++r.dropped;
    }
  }
  reports_.clear();
  for (auto& [id, r] : by_id) reports_.push_back(std::move(r));
  return keep;
}

ObjectSnapshot DynamicObjects::Snapshot(int64_t t_ns, const FrameFeatures& f, uint16_t id, const cv::Mat& instance_id,
                                        const Eigen::Isometry3d& T_w_c) const {
  const int r = settings_.adaptive.interior_px;
  std::vector<std::pair<float, int>> by_depth;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.object[i] != id || !(f.depth[i] > 0)) continue;
    if (r > 0 && !instance_id.empty() && !InteriorOf(instance_id, f.keypoints[i], id, r)) continue;
    by_depth.emplace_back(f.depth[i], static_cast<int>(i));
  }
  std::sort(by_depth.begin(), by_depth.end());
  const float band = static_cast<float>(settings_.adaptive.foreground_band_m);
  // Stereo can put a cluster of the object's features far in front of it: a person's two legs
  // carry the same texture, and a left-right match across them gives a disparity 100 px too
  // large (depth 0.11 m for legs at 0.66 m, standing_then_walking). When such a cluster holds a
  // quarter of the features it becomes the quartile below and the snapshot keeps only it, a
  // false half-metre motion. So features nearer by more than the band than the densest depth
  // band of the object (the window of that width holding most features, the nearest on a tie)
  // are dropped first.
  if (!by_depth.empty()) {
    size_t best_start = 0, best_count = 0;
    for (size_t lo = 0, hi = 0; lo < by_depth.size(); ++lo) {
      while (hi < by_depth.size() && by_depth[hi].first <= by_depth[lo].first + band) ++hi;
      if (hi - lo > best_count) {
        best_count = hi - lo;
        best_start = lo;
      }
    }
    const float min_z = by_depth[best_start].first - band;
    size_t first = 0;
    while (first < by_depth.size() && by_depth[first].first < min_z) ++first;
    by_depth.erase(by_depth.begin(), by_depth.begin() + static_cast<std::ptrdiff_t>(first));
  }
  // A mask is loose (dilated, jittered): background seen past the object's edges falls inside it
  // and, being static, would match perfectly over time. Keep the object's own depth band.
  if (!by_depth.empty()) {
    const float max_z = by_depth[by_depth.size() / 4].first + band;
    while (!by_depth.empty() && by_depth.back().first > max_z) by_depth.pop_back();
  }
  if (by_depth.size() > kMaxSnapshotPoints) by_depth.resize(kMaxSnapshotPoints);
  const double median_depth = by_depth.empty() ? 0.0 : static_cast<double>(by_depth[by_depth.size() / 2].first);
  ObjectSnapshot s;
  s.t_ns = t_ns;
  s.T_c_w = T_w_c.inverse();
  s.depth_m = median_depth;
  s.descriptors.create(static_cast<int>(by_depth.size()), f.descriptors.cols, f.descriptors.type());
  const double sigma_d = settings_.adaptive.disparity_sigma_px, sigma_px = settings_.adaptive.pixel_sigma_px;
  for (size_t k = 0; k < by_depth.size(); ++k) {
    const auto [z, i] = by_depth[k];
    const Eigen::Vector3d p_c = f.Unproject(cam_, i);
    s.p_w.push_back(T_w_c * p_c);
    // Depth error moves a point along its ray (range / z times the depth error); the keypoint's
    // position error moves it across, by range * angle.
    const double range = p_c.norm();
    s.sigma_m.push_back(static_cast<double>(z) * z * sigma_d / cam_.bf * (range / static_cast<double>(z)));
    const size_t level = static_cast<size_t>(std::max(0, f.keypoints[static_cast<size_t>(i)].octave));
    const double scale = level < f.level_scale.size() ? f.level_scale[level] : 1.0;
    s.sigma_lateral_m.push_back(range * sigma_px * scale / cam_.fx);
    f.descriptors.row(i).copyTo(s.descriptors.row(static_cast<int>(k)));
  }
  return s;
}

std::map<uint16_t, double> DynamicObjects::LabelledPointNorms(const cv::Mat& instance_id, const Eigen::Isometry3d& T_c_w,
                                                              const std::vector<Eigen::Vector3d>& map_points_w) const {
  std::map<uint16_t, std::pair<double, int>> sums;
  if (instance_id.empty()) return {};
  for (const Eigen::Vector3d& p_w : map_points_w) {
    const Eigen::Vector3d p_c = T_c_w * p_w;
    if (p_c.z() <= 0) continue;
    const Eigen::Vector2d uv = cam_.Project(p_c);
    if (!cam_.InImage(uv.x(), uv.y())) continue;
    const uint16_t id = instance_id.at<uint16_t>(static_cast<int>(std::lround(uv.y())), static_cast<int>(std::lround(uv.x())));
    if (id == 0) continue;
    auto& [sum, n] = sums[id];
    sum += p_w.norm();
    ++n;
  }
  std::map<uint16_t, double> out;
  for (const auto& [id, sn] : sums) out[id] = sn.first / sn.second;
  return out;
}

void DynamicObjects::DropFromFrame(const std::vector<uint16_t>& ids) {
  for (ObjectReport& r : reports_) {
    if (std::find(ids.begin(), ids.end(), r.id) != ids.end()) r.dropped = r.features;
  }
}

void DynamicObjects::RestartMeasurements() {
  for (auto& [id, o] : objects_) o.motion.RestartMeasurements();
}

std::vector<uint16_t> DynamicObjects::Update(int64_t t_ns, const FrameFeatures& f, const cv::Mat& instance_id,
                                             const Eigen::Isometry3d& T_c_w,
                                             const std::vector<Eigen::Vector3d>& map_points_w,
                                             const Eigen::Isometry3d* T_c_w_tracked) {
  std::vector<uint16_t> turned;
  just_confirmed_.clear();
  const int64_t forget_ns = static_cast<int64_t>(settings_.forget_s * 1e9);
  for (auto it = objects_.begin(); it != objects_.end();) {
    it = t_ns - it->second.last_seen_ns > forget_ns ? objects_.erase(it) : std::next(it);
  }
  if (method_ == DynamicMethod::kNone) return turned;
  const Eigen::Isometry3d T_w_c = T_c_w.inverse();
  // A point that would lie within kBorderPx of the edge of the other snapshot's image (the
  // current one for a reference point, the reference one for a current point) cannot have been
  // detected there (ORB needs a 31 px patch, 37 px on the second level): only its look-alikes can
  // match it.
  constexpr double kBorderPx = 40;
  const InViewIfStatic in_view = [this](const Eigen::Isometry3d& T_cam_w, const Eigen::Vector3d& p_w) {
    const Eigen::Vector3d p_c = T_cam_w * p_w;
    if (p_c.z() <= 0) return false;
    const Eigen::Vector2d uv = cam_.Project(p_c);
    return uv.x() >= kBorderPx && uv.y() >= kBorderPx && uv.x() <= cam_.width - 1 - kBorderPx &&
           uv.y() <= cam_.height - 1 - kBorderPx;
  };
  std::map<uint16_t, double> norms;
  if (method_ == DynamicMethod::kPaper) norms = LabelledPointNorms(instance_id, T_c_w, map_points_w);
  std::map<uint16_t, Silhouette> silhouettes;
  // The masks' silhouettes, for the adaptive test's look at a mask that moves (one pass over the image).
  if (method_ == DynamicMethod::kAdaptive && settings_.adaptive.silhouette_threshold_m > 0) {
    std::set<uint16_t> ids;
    for (const ObjectReport& r : reports_) ids.insert(r.id);
    // Each instance's median feature depth: a neighbour behind an object does not hide its edge.
    std::map<uint16_t, std::vector<float>> depths;
    for (size_t i = 0; i < f.size(); ++i) {
      if (f.object[i] != 0 && f.depth[i] > 0) depths[f.object[i]].push_back(f.depth[i]);
    }
    std::map<uint16_t, double> depth_m;
    for (auto& [id, z] : depths) {
      std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
      depth_m[id] = z[z.size() / 2];
    }
    silhouettes = ExtractSilhouettes(instance_id, ids, static_cast<int>(kBorderPx), depth_m,
                                     settings_.adaptive.silhouette_behind_m);
    for (auto& [id, sil] : silhouettes) sil.T_c_w = T_c_w_tracked != nullptr ? *T_c_w_tracked : T_c_w;
  }
  for (ObjectReport& r : reports_) {
    ObjectState& o = objects_[r.id];
    o.last_seen_ns = t_ns;
    const bool was = o.dynamic, was_confirmed = o.confirmed;
    switch (method_) {
      case DynamicMethod::kSemantic:
        o.dynamic = true;
        break;
      case DynamicMethod::kPaper: {
        std::vector<float> depths;
        for (size_t i = 0; i < f.size(); ++i) {
          if (f.object[i] == r.id) depths.push_back(f.depth[i]);
        }
        const auto n = norms.find(r.id);
        o.dynamic = o.paper.Add(t_ns, n == norms.end() ? 0.0 : n->second, MeanMaskDepth(depths),
                                CategoryPrior(r.category, settings_.prior), settings_);
        r.score = o.paper.last_delta_a();
        r.threshold = settings_.th_d;
        break;
      }
      case DynamicMethod::kAdaptive: {
        ObjectSnapshot snap = Snapshot(t_ns, f, r.id, instance_id, T_w_c);
        const auto sil = silhouettes.find(r.id);
        if (sil != silhouettes.end()) snap.silhouette = std::move(sil->second);
        o.dynamic = o.motion.Add(std::move(snap), settings_.adaptive, in_view, &cam_);
        r.score = o.motion.last().displacement_m;
        r.threshold = o.motion.last().threshold_m;
        break;
      }
      case DynamicMethod::kNone:
        break;
    }
    r.dynamic = o.dynamic;
    // Only the adaptive test has tentative decisions; the others' are confirmed when made.
    o.confirmed = method_ == DynamicMethod::kAdaptive ? o.motion.confirmed() : o.dynamic;
    if (o.dynamic && !was) turned.push_back(r.id);
    if (o.confirmed && !was_confirmed) just_confirmed_.push_back(r.id);
  }
  return turned;
}

int64_t DynamicObjects::MotionOnsetNs(uint16_t id) const {
  if (method_ != DynamicMethod::kAdaptive) return kUndatedMotion;
  const auto it = objects_.find(id);
  return it == objects_.end() ? kUndatedMotion : it->second.motion.motion_onset_ns();
}

}  // namespace viqu::slam

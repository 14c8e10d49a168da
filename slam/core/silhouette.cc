#include "slam/core/silhouette.h"

#include <algorithm>
#include <cmath>

#include "slam/core/median.h"

namespace viqu::slam {
namespace {

// Median and its standard error of one side's end shifts.
struct Side {
  double median = 0, std_error = 0;
};
Side SideOf(const std::vector<double>& d) {
  Side s;
  s.median = Median(d);
  std::vector<double> dev(d.size());
  for (size_t k = 0; k < d.size(); ++k) dev[k] = std::abs(d[k] - s.median);
  // The ends' spread by the median absolute deviation (1.4826: to a standard deviation), and the
  // median's standard error over independent ends: neighbouring rows share the mask's noise, so
  // about one in four sampled rows (8 px) counts as independent.
  constexpr double kMadToSigma = 1.4826, kRowsPerIndependent = 4;
  const double sigma = kMadToSigma * Median(dev);
  s.std_error = kMedianEfficiency * sigma / std::sqrt(std::max(1.0, d.size() / kRowsPerIndependent));
  return s;
}

}  // namespace

int Silhouette::RowIndex(int row) const {
  const auto it = std::lower_bound(v.begin(), v.end(), row);
  return it != v.end() && *it == row ? static_cast<int>(it - v.begin()) : -1;
}

std::map<uint16_t, Silhouette> ExtractSilhouettes(const cv::Mat& instance_id, const std::set<uint16_t>& ids,
                                                  int border_px, const std::map<uint16_t, double>& depth_m,
                                                  double behind_m) {
  std::map<uint16_t, Silhouette> out;
  if (instance_id.empty() || ids.empty()) return out;
  const int w = instance_id.cols;
  const std::vector<uint16_t> list(ids.begin(), ids.end());
  std::vector<int> slot(static_cast<size_t>(list.back()) + 1, -1);  // id -> index in list
  for (size_t i = 0; i < list.size(); ++i) slot[list[i]] = static_cast<int>(i);
  // Whether instance `nb` lies behind object `id` by more than behind_m (both with a depth).
  const auto behind = [&](uint16_t nb, uint16_t id) {
    const auto a = depth_m.find(id), b = depth_m.find(nb);
    return a != depth_m.end() && b != depth_m.end() && b->second > a->second + behind_m;
  };
  struct Extent {
    int lo = -1, hi = -1;
  };
  std::vector<Extent> ext(list.size());
  std::vector<bool> present(65536, false);
  std::vector<std::set<uint16_t>> touches_lo(list.size()), touches_hi(list.size());
  std::vector<Silhouette> sil(list.size());
  for (int y = 0; y < instance_id.rows; y += kSilhouetteRowStep) {
    const uint16_t* row = instance_id.ptr<uint16_t>(y);
    std::fill(ext.begin(), ext.end(), Extent());
    for (int x = 0; x < w; ++x) {
      const uint16_t id = row[x];
      if (id == 0) continue;
      present[id] = true;
      const int k = id < slot.size() ? slot[id] : -1;
      if (k < 0) continue;
      if (ext[static_cast<size_t>(k)].lo < 0) ext[static_cast<size_t>(k)].lo = x;
      ext[static_cast<size_t>(k)].hi = x;
    }
    for (size_t k = 0; k < list.size(); ++k) {
      const Extent& e = ext[k];
      if (e.lo < 0) continue;
      const uint16_t id = list[k];
      // An end is the object's own edge where it meets the background or an instance behind it;
      // one that meets a nearer instance (or whose neighbour's depth is unknown) may be where that
      // instance hides it. Ends at the image's edge are left out.
      const auto own_edge = [&](int x_out, std::set<uint16_t>* touches) {
        if (x_out < 0 || x_out >= w) return false;
        const uint16_t nb = row[x_out];
        if (nb == 0 || behind(nb, id)) return true;
        touches->insert(nb);
        return false;
      };
      const bool lo = own_edge(e.lo - 1, &touches_lo[k]) && e.lo >= border_px;
      const bool hi = own_edge(e.hi + 1, &touches_hi[k]) && e.hi <= w - 1 - border_px;
      if (!lo && !hi) continue;
      sil[k].v.push_back(y);
      sil[k].lo.push_back(lo ? e.lo : -1);
      sil[k].hi.push_back(hi ? e.hi : -1);
    }
  }
  std::vector<uint16_t> frame_ids;
  for (size_t id = 1; id < present.size(); ++id) {
    if (present[id]) frame_ids.push_back(static_cast<uint16_t>(id));
  }
  for (size_t k = 0; k < list.size(); ++k) {
    if (sil[k].empty()) continue;
    Silhouette& s = out[list[k]];
    s = std::move(sil[k]);
    s.frame_ids = frame_ids;
    s.touches_lo.assign(touches_lo[k].begin(), touches_lo[k].end());
    s.touches_hi.assign(touches_hi[k].begin(), touches_hi[k].end());
  }
  return out;
}

SilhouetteShift MeasureSilhouetteShift(const Silhouette& ref, double z_ref, const Silhouette& cur, const StereoCamera& cam,
                                       int min_side_rows) {
  SilhouetteShift out;
  if (ref.empty() || cur.empty() || !(z_ref > 0)) return out;
  const auto all_in = [](const std::vector<uint16_t>& ids, const std::vector<uint16_t>& sorted) {
    for (const uint16_t id : ids) {
      if (!std::binary_search(sorted.begin(), sorted.end(), id)) return false;
    }
    return true;
  };
  // Sides whose neighbours are present in both frames (left, right).
  const bool comparable[2] = {all_in(ref.touches_lo, cur.frame_ids) && all_in(cur.touches_lo, ref.frame_ids),
                              all_in(ref.touches_hi, cur.frame_ids) && all_in(cur.touches_hi, ref.frame_ids)};
  const Eigen::Isometry3d T_cur_ref = cur.T_c_w * ref.T_c_w.inverse();
  std::vector<double> d[2];  // left ends, right ends
  for (size_t k = 0; k < ref.v.size(); ++k) {
    for (const bool left : {true, false}) {
      if (!comparable[left ? 0 : 1]) continue;
      const int u = left ? ref.lo[k] : ref.hi[k];
      if (u < 0) continue;
      const Eigen::Vector3d p = T_cur_ref * cam.Unproject(u, ref.v[k], z_ref);
      if (p.z() <= 0) continue;
      const Eigen::Vector2d uv = cam.Project(p);
      // The current row nearest the carried end, and its end on the same side.
      const int r = static_cast<int>(std::lround(uv.y() / kSilhouetteRowStep)) * kSilhouetteRowStep;
      const int i = cur.RowIndex(r);
      if (i < 0) continue;
      const int u_cur = left ? cur.lo[static_cast<size_t>(i)] : cur.hi[static_cast<size_t>(i)];
      if (u_cur >= 0) d[left ? 0 : 1].push_back(u_cur - uv.x());
    }
  }
  const bool has[2] = {static_cast<int>(d[0].size()) >= std::max(1, min_side_rows),
                       static_cast<int>(d[1].size()) >= std::max(1, min_side_rows)};
  if (has[0] && has[1]) {
    const Side l = SideOf(d[0]), r = SideOf(d[1]);
    out.rows = static_cast<int>(d[0].size() + d[1].size());
    out.shift_px = 0.5 * (l.median + r.median);
    out.std_error_px = 0.5 * std::hypot(l.std_error, r.std_error);
    out.two_sided = true;
  } else if (has[0] || has[1]) {
    const std::vector<double>& one = has[0] ? d[0] : d[1];
    const Side s = SideOf(one);
    out.rows = static_cast<int>(one.size());
    out.shift_px = s.median;
    out.std_error_px = s.std_error;
  }
  return out;
}

}  // namespace viqu::slam

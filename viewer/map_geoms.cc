#include "viewer/map_geoms.h"

#include <algorithm>

namespace viqu::viewer {

std::vector<int> ThinPath(int n, int max_segments) {
  std::vector<int> keep;
  if (n <= 0) return keep;
  const int step = max_segments <= 0 ? n : std::max(1, (n - 1 + max_segments - 1) / max_segments);
  for (int i = 0; i < n; i += step) keep.push_back(i);
  if (keep.back() != n - 1) keep.push_back(n - 1);
  return keep;
}

namespace {

mjvGeom* NextGeom(mjvScene* scn) {
  if (scn->ngeom >= scn->maxgeom) return nullptr;
  return &scn->geoms[scn->ngeom++];
}

}  // namespace

int AddMapGeoms(const MapDrawing& drawing, const MapStyle& style, mjvScene* scn) {
  const int before = scn->ngeom;
  for (const MapDrawing::Path& path : drawing.paths) {
    const std::vector<int> keep = ThinPath(static_cast<int>(path.points.size()), style.max_path_segments);
    for (size_t i = 1; i < keep.size(); ++i) {
      mjvGeom* g = NextGeom(scn);
      if (g == nullptr) return scn->ngeom - before;
      mjv_initGeom(g, mjGEOM_LINE, nullptr, nullptr, nullptr, path.rgba);
      const Eigen::Vector3d& a = path.points[static_cast<size_t>(keep[i - 1])];
      const Eigen::Vector3d& b = path.points[static_cast<size_t>(keep[i])];
      mjv_makeConnector(g, mjGEOM_LINE, style.line_width_px, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
    }
  }
  const size_t n = drawing.map_points.size();
  const size_t first = n > static_cast<size_t>(std::max(style.max_map_points, 0))
                           ? n - static_cast<size_t>(std::max(style.max_map_points, 0))
                           : 0;
  const mjtNum size[3] = {style.point_half_size_m, style.point_half_size_m, style.point_half_size_m};
  for (size_t i = first; i < n; ++i) {
    mjvGeom* g = NextGeom(scn);
    if (g == nullptr) break;
    const Eigen::Vector3d& p = drawing.map_points[i];
    const mjtNum pos[3] = {p.x(), p.y(), p.z()};
    const bool object = i < drawing.on_object.size() && drawing.on_object[i] != 0;
    mjv_initGeom(g, mjGEOM_BOX, size, pos, nullptr, object ? style.object_point_rgba : style.point_rgba);
  }
  return scn->ngeom - before;
}

}  // namespace viqu::viewer

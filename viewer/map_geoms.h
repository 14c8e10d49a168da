#pragma once
// What the SLAM side looks like in the viewer's 3D scene: trajectories as lines (ground truth,
// SLAM estimate) and the map points as small boxes, appended to a MuJoCo abstract scene after
// mjv_updateScene. No GL here: the scene is plain data, so this is testable without a display.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <mujoco/mujoco.h>

namespace viqu::viewer {

struct MapDrawing {
  struct Path {
    std::vector<Eigen::Vector3d> points;  // in order (m, world)
    float rgba[4] = {1, 1, 1, 1};
  };
  std::vector<Path> paths;
  std::vector<Eigen::Vector3d> map_points;  // (m, world), oldest first
  std::vector<uint8_t> on_object;           // per map point: created on a segmented object
};

// Drawing limits: the software renderer draws each geom on its own, so long runs are thinned
// (a path keeps every k-th point and its last; the newest map points are kept).
struct MapStyle {
  int max_path_segments = 400;      // per path
  int max_map_points = 1500;       // the newest (each box is its own draw call: about 10 us in llvmpipe)
  double point_half_size_m = 0.006;  // half edge of a map point's box (m)
  double line_width_px = 3;          // path line width (px)
  float point_rgba[4] = {0.15f, 0.35f, 1.0f, 1};     // map point on the static scene (blue)
  float object_point_rgba[4] = {0.9f, 0.1f, 0.1f, 1};  // map point created on an object
};

// The indices of `n` path points kept under `max_segments` (first and last always kept).
std::vector<int> ThinPath(int n, int max_segments);

// Appends the drawing to `scn` (as many geoms as fit in scn->maxgeom; paths first, then the
// newest map points). Returns the number of geoms added.
int AddMapGeoms(const MapDrawing& drawing, const MapStyle& style, mjvScene* scn);

}  // namespace viqu::viewer

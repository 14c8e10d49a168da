#pragma once
// Hand-placed keyframes and map points for the map and matcher tests: a keyframe with one
// monocular feature where a chosen world point projects, every feature the same descriptor, so
// that only geometry tells points apart.
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "slam/core/map.h"

namespace viqu::testing {

// A frame at camera centre `c` (looking along the world's +z) with one monocular feature where
// `p_w` projects, at pyramid level `level`, taken at `t_ns`.
inline slam::Frame MakeFrame(const slam::StereoCamera& cam, const Eigen::Vector3d& c, const Eigen::Vector3d& p_w,
                             int level, int64_t t_ns = 0) {
  auto f = std::make_shared<slam::FrameFeatures>();
  const Eigen::Vector2d uv = cam.Project(p_w - c);
  f->keypoints = {slam::FeaturePoint(cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y())), level)};
  f->descriptors = cv::Mat(1, 32, CV_8U, cv::Scalar(0x5a));
  f->u_right = {-1.f};
  f->depth = {-1.f};
  f->object = {0};
  for (int l = 0; l < 8; ++l) {
    f->level_scale.push_back(static_cast<float>(std::pow(1.2, l)));
    f->level_sigma2.push_back(f->level_scale.back() * f->level_scale.back());
  }
  f->BuildGrid(cam.width, cam.height);
  slam::Frame frame;
  frame.Reset(f);
  frame.t_ns = t_ns;
  frame.T_c_w = Eigen::Isometry3d(Eigen::Translation3d(-c));
  return frame;
}

// The same as a keyframe of `map`.
inline slam::KeyFrame* AddKeyFrame(slam::Map* map, const slam::StereoCamera& cam, const Eigen::Vector3d& c,
                                   const Eigen::Vector3d& p_w, int level, int64_t t_ns = 0) {
  return map->AddKeyFrame(MakeFrame(cam, c, p_w, level, t_ns));
}

// A map point at `p_w` observed by feature 0 of each of `observers` (the first made it).
inline slam::MapPoint* AddPoint(slam::Map* map, const Eigen::Vector3d& p_w, const std::vector<slam::KeyFrame*>& observers) {
  slam::MapPoint* p = map->AddPoint(p_w, observers.front());
  for (slam::KeyFrame* kf : observers) slam::Map::AddObservation(p, kf, 0);
  p->UpdateFromObservations();
  return p;
}

}  // namespace viqu::testing

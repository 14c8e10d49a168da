#pragma once
// video.mp4 of a run (`viqu run --video`): the left image with what SLAM made of it. Features
// coloured by their fate (tracked: green, new map point: cyan, dropped on a dynamic object:
// red, unmatched: yellow), instance masks tinted per object with the object's name and state,
// and the frame's time, status, inliers and position error in a corner. MPEG-4 Part 2 in an
// .mp4 (OpenCV's own encoder; VLC and ffmpeg play it), written under a temporary name.
#include <string>

#include <opencv2/core/mat.hpp>
#include <opencv2/videoio.hpp>

#include "slam/core/slam_system.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::runner {

class OverlayVideo {
 public:
  OverlayVideo(const std::string& path, double fps, int width, int height);
  ~OverlayVideo();
  OverlayVideo(const OverlayVideo&) = delete;
  OverlayVideo& operator=(const OverlayVideo&) = delete;

  // One frame: `track` null without SLAM (the plain image); `error_m` < 0 when unknown.
  void Add(const StereoFrame& frame, const slam::TrackResult* track, double error_m);
  // Renames the finished video onto its final name.
  void Finish();

  // The overlay image (BGR) of one frame, as Add() writes it (for tests).
  static cv::Mat Draw(const StereoFrame& frame, const slam::TrackResult* track, double error_m);

 private:
  std::string path_, tmp_;
  cv::VideoWriter writer_;
  bool done_ = false;
};

}  // namespace viqu::runner

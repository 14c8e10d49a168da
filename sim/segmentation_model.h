#pragma once
// Imitates a real instance-segmentation detector on the simulator's ideal instance image:
// missed detections, loose (dilated) masks and latency. Pure C++/OpenCV on plain inputs (no
// MuJoCo), applied to a StereoFrame after rendering.
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "scenario/scenario.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {

// Per Apply(frame), on frame->left_instance_id (CV_16UC1) and frame->instances:
// 1. Misses: every listed instance with id != 0 whose category is neither background nor robot
//    (the "detectable" ones: person, box, ball, furniture) is dropped, independently per frame,
//    with probability miss_rate: its pixels become 0 and its entry leaves `instances`. One
//    uniform draw per detectable instance, in ascending id order, whatever miss_rate is.
//    Background and robot pixels (the robot's self-mask comes from its own kinematics, not a
//    detector) are never dropped nor dilated.
// 2. Dilation: each kept detectable instance grows by dilate_px pixels with a square
//    (2*dilate_px+1) structuring element, so an axis-aligned rectangle grows by exactly dilate_px
//    on every side. Growth only claims pixels that are 0 after step 1 (background or a dropped
//    instance), never another instance's own pixels. Where several instances grow into the same
//    pixel, the nearer one wins: nearer = smaller median of its pixels' finite positive depths in
//    frame->left_depth_m (CV_32FC1, same size); without depth (or without a valid depth for an
//    instance, treated as infinitely far) the lower id wins.
// 3. Latency: the frame receives the mask (image and instance list) computed latency_frames
//    calls earlier; during the first latency_frames calls it receives an empty mask (all zeros,
//    instances reduced to the frame's own id-0 entries).
// Frames without an instance image (segmentation not rendered) are left alone and do not
// advance the model. Deterministic given the seed and the sequence of frames.
class SegmentationModel {
 public:
  // Throws viqu::InputError for miss_rate outside [0, 1], or negative dilate_px / latency_frames.
  SegmentationModel(const viqu::SegmentationConfig& config, uint64_t seed);

  // Replaces frame->left_instance_id and frame->instances as described above. Throws
  // viqu::InputError for a null frame or an instance image that is not CV_16UC1.
  void Apply(viqu::StereoFrame* frame);

 private:
  // The detector's output for one frame.
  struct Detection {
    cv::Mat instance_id;                          // CV_16UC1 instance ids (0 = background)
    std::vector<viqu::SegmentInstance> instances;  // entries of the ids present
  };

  Detection Detect(const viqu::StereoFrame& frame);  // steps 1 and 2

  viqu::SegmentationConfig config_;
  std::mt19937_64 rng_;
  std::deque<Detection> pending_;  // detections waiting out the latency, oldest first
};

}  // namespace viqu::sim

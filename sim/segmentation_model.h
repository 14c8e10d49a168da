#pragma once
// Imitates a real instance-segmentation detector on the simulator's ideal instance image:
// missed detections, a minimum detectable area, wrong categories, loose (dilated) and flickering
// (jittered) masks, spurious masks on the background, and latency. Pure C++/OpenCV on plain inputs
// (no MuJoCo), applied to a StereoFrame after rendering.
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "scenario/scenario.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {

// Per Apply(frame), on frame->left_instance_id (CV_16UC1) and frame->instances. The
// "detectable" instances are the listed ones with id != 0 whose category is neither background
// nor robot (person, box, ball, furniture). Background and robot pixels (the robot's self-mask
// comes from its own kinematics, not a detector) are never dropped, relabelled, dilated or eroded.
// 1. Misses: every detectable instance is dropped, independently per frame, with probability
//    miss_rate: its pixels become 0 and its entry leaves `instances`.
// 2. Minimum area: a detectable instance with fewer than min_area_px pixels in the ideal image
//    (its visible pixels, before any growth or shrinking) is dropped in the same way. A listed
//    instance without pixels is therefore dropped whenever min_area_px >= 1.
// 3. Wrong category: each instance kept by steps 1-2 is reported, with probability
//    wrong_category_rate, as one of the three other categories of {person, box, ball,
//    furniture}, each equally likely (never background or robot). Its id and name stay.
// 4. Boundary: each kept instance's mask grows by r = dilate_px + d pixels, d a uniform integer
//    in [-boundary_jitter_px, +boundary_jitter_px] drawn per instance and frame, with a square
//    (2|r|+1) structuring element, so an axis-aligned rectangle moves by exactly r on every side:
//    - r < 0 (shrinking) is applied first: the instance's pixels within |r| of a pixel that is
//      not its own become 0; the image border does not erode (the object continues beyond it).
//      An instance eroded to nothing leaves `instances`.
//    - r > 0 (growing) follows, and only claims pixels that are 0 at that point (background, a
//      dropped instance, or pixels freed by shrinking), never another instance's own pixels.
//      Where several instances grow into the same pixel, the nearer one wins: nearer = smaller
//      median of its pixels' finite positive depths in frame->left_depth_m (CV_32FC1, same
//      size); without depth (or without a valid depth for an instance, treated as infinitely
//      far) the lower id wins.
// 5. Spurious masks: with probability false_positive_rate per frame, one blob on the background
//    is added as a new instance: a filled ellipse centred on a pixel drawn uniformly among the
//    pixels that are 0 after step 4, semi-axes drawn uniformly in [kSpuriousMinSemiAxisPx,
//    kSpuriousMaxSemiAxisPx] (integers) and orientation uniform in [0, 180) deg; it takes only the
//    ellipse's pixels that are 0 (never another instance's). Its category is person, box or ball,
//    equally likely; its name is `spurious_<n>` with n = 1, 2, ... counting this model's
//    spurious masks. Its id is new each time: ids count down from 65535 within (highest id seen
//    in any input frame so far, 65535], wrapping to 65535 when the range is used up, so a
//    spurious mask never shares an id with a real instance of the frames seen so far and never
//    continues another spurious mask's history until the range wraps (tens of thousands of
//    spurious masks later). Nothing is added to a frame without a 0 pixel, nor once an input id
//    of 65535 has been seen (no id left). min_area_px does not apply to spurious masks (an
//    unclipped one covers at least pi * 8^2 = 201 px), so false_positive_rate is the rate of
//    spurious masks actually produced.
// 6. Latency: the frame receives the mask (image and instance list) computed latency_frames
//    calls earlier; during the first latency_frames calls it receives an empty mask (all zeros,
//    instances reduced to the frame's own id-0 entries).
// Random draws: each random step has its own std::mt19937_64 stream, and draws a fixed number of
// values per frame that depends only on the frame's detectable ids (never on any setting), so
// changing one step's setting never changes another step's outcomes:
//  - misses: the stream seeded with `seed` itself (as before the other steps existed); one
//    std::uniform_real_distribution<double>(0, 1) draw per detectable instance, in ascending id
//    order, whatever miss_rate is;
//  - wrong category: two draws per detectable instance, in ascending id order (whether to relabel,
//    which category), whether or not the instance was dropped;
//  - boundary jitter: one draw per detectable instance, in ascending id order, likewise;
//  - spurious masks: six draws per frame (whether, category, centre, two semi-axes, angle).
// The three newer streams (wrong category, jitter, spurious) are seeded with outputs k = 1, 2, 3
// of a SplitMix64 generator started at `seed` (its mixing function of seed + k *
// 0x9E3779B97F4A7C15), and each of their draws takes exactly one 64-bit output: its top 53 bits
// as a uniform u in [0, 1), and an integer in [0, n) as floor(u * n).
// With min_area_px 0, wrong_category_rate 0, boundary_jitter_px 0 and false_positive_rate 0 the
// output is that of misses, dilation and latency alone.
// Defaults (scenario/scenario.h SegmentationConfig), a good detector: miss_rate 0.05, dilate_px 2,
// latency_frames 0, min_area_px 150 (about 12 x 12 px, 0.05% of a 640 x 480 image: objects
// smaller than that are where instance segmenters such as Mask R-CNN or YOLOv8-seg lose most of
// their recall; at the default 70 deg vertical field of view a person 10 m away still covers
// several hundred px, a 0.2 m ball is detected out to about 5 m, and an object entering at the
// image edge is reported once 150 px of it are in view),
// false_positive_rate 0 and wrong_category_rate 0 (the shipped scenes are clean, with few and
// distinct objects), boundary_jitter_px 1 (masks flicker by one pixel at the edges, so with
// dilate_px 2 they grow by 1, 2 or 3 px from frame to frame).
// Frames without an instance image (segmentation not rendered) are left alone and do not
// advance the model. Deterministic given the seed and the sequence of frames.
class SegmentationModel {
 public:
  // Smallest and largest semi-axis of a spurious ellipse (px), step 5.
  static constexpr int kSpuriousMinSemiAxisPx = 8;
  static constexpr int kSpuriousMaxSemiAxisPx = 40;

  // Throws viqu::InputError for miss_rate, false_positive_rate or wrong_category_rate outside
  // [0, 1], or negative dilate_px / latency_frames / min_area_px / boundary_jitter_px.
  SegmentationModel(const viqu::SegmentationConfig& config, uint64_t seed);

  // Replaces frame->left_instance_id and frame->instances as described above. Throws
  // viqu::InputError for a null frame or an instance image that is not CV_16UC1.
  void Apply(viqu::StereoFrame* frame);

  // Whether masks may grow (step 4: dilate_px + boundary_jitter_px > 0), so that the frames need
  // left_depth_m for the nearest-first order: without it the order is by id, another result.
  static bool GrowsMasks(const viqu::SegmentationConfig& config) {
    return config.dilate_px + config.boundary_jitter_px > 0;
  }

 private:
  // The detector's output for one frame.
  struct Detection {
    cv::Mat instance_id;                          // CV_16UC1 instance ids (0 = background)
    std::vector<viqu::SegmentInstance> instances;  // entries of the ids present
  };

  Detection Detect(const viqu::StereoFrame& frame);  // steps 1 to 5
  // Step 5 on `out`, using the next spurious_rng_ draws.
  void AddSpurious(Detection* out);

  viqu::SegmentationConfig config_;
  std::mt19937_64 rng_;           // misses
  std::mt19937_64 category_rng_;  // wrong categories
  std::mt19937_64 jitter_rng_;    // boundary jitter
  std::mt19937_64 spurious_rng_;  // spurious masks
  int max_input_id_ = 0;          // highest id seen in any input frame (image or list)
  int next_spurious_id_ = 65535;  // the next spurious mask's id, counting down
  int spurious_count_ = 0;        // spurious masks made so far
  std::deque<Detection> pending_;  // detections waiting out the latency, oldest first
};

}  // namespace viqu::sim

#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "common/atomic_output_file.h"
#include "sim/image_write_queue.h"
#include "sim/trajectory_writer.h"
#include "slam/measurements/ground_truth_pose.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {

// Records the left camera of a run in the TUM RGB-D layout, which RGB-D SLAM systems and TUM's
// evaluation scripts read as is:
//
//   DATASET/rgb/<t>.png       left RGB (8-bit colour PNG)
//   DATASET/depth/<t>.png     left depth, 16-bit PNG, value = depth (m) * 5000, 0 = no depth
//   DATASET/rgb.txt, depth.txt   "t filename" per image, '#' header lines
//   DATASET/groundtruth.txt   left camera optical frame in world, "t tx ty tz qx qy qz qw"
//   DATASET/camera.yaml       fx, fy, cx, cy, width, height, depth_scale of this recording
//
// <t> and t are seconds with 9 decimals, exact from the nanosecond stamps. Everything is
// written under DATASET.partial/ and renamed onto DATASET by Finish(); destroyed without
// Finish(), the recorder removes DATASET.partial. Stamps of each stream must increase. Errors
// throw RunError. Threads: AddFrame and AddGroundTruth share no state, so each may be called on
// its own thread (one at a time each); Finish after both.
class TumRecorder {
 public:
  // `dataset_dir` is the final folder; a stale DATASET.partial is replaced.
  TumRecorder(const std::string& dataset_dir, const PinholeIntrinsics& intrinsics);
  ~TumRecorder();
  TumRecorder(const TumRecorder&) = delete;
  TumRecorder& operator=(const TumRecorder&) = delete;

  // Left RGB (CV_8UC3, RGB order) and, when not empty, left depth (CV_32F, m). `depth_steps`,
  // when given, is the depth already in steps (sim::QuantiseDepth's result at kDepthScale): it
  // is written as is (and must not be modified afterwards) instead of being converted again.
  void AddFrame(const StereoFrame& frame, const cv::Mat& depth_steps = cv::Mat());
  // The left camera pose (state.T_w_cam) at state.t_ns.
  void AddGroundTruth(const GroundTruthState& state);
  // Writes camera.yaml, commits the lists and renames the folder into place.
  void Finish();

  const std::string& dataset_dir() const { return final_dir_; }
  const std::string& partial_dir() const { return partial_dir_; }

  static constexpr double kDepthScale = 5000;  // depth PNG value per metre (TUM's convention)

 private:
  // One list file with the stamp of its last row.
  struct ListStream {
    std::unique_ptr<AtomicOutputFile> file;                   // rgb.txt or depth.txt, temporary name
    int64_t last_t_ns = std::numeric_limits<int64_t>::min();  // stamp of the last row (ns)
  };
  void WriteImage(const char* folder, ListStream* list, int64_t t_ns, const cv::Mat& image, PngContent content);

  std::string final_dir_;    // DATASET
  std::string partial_dir_;  // DATASET.partial
  PinholeIntrinsics intrinsics_;
  ListStream rgb_, depth_;
  std::unique_ptr<TrajectoryWriter> groundtruth_;  // groundtruth.txt
  int64_t last_gt_t_ns_ = std::numeric_limits<int64_t>::min();  // stamp of the last pose (ns)
  std::unique_ptr<ImageWriteQueue> writer_ = std::make_unique<ImageWriteQueue>();  // PNG encoding
  bool finished_ = false;    // Finish() succeeded
};

}  // namespace viqu::sim

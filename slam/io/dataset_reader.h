#pragma once
// The interface of every offline dataset: frames in time order plus what is known about them.
// `viqu slam DIR --format viqu|euroc|tum` opens one through OpenDataset (open_dataset.h).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "slam/io/frame_skip_policy.h"
#include "slam/measurements/ground_truth_pose.h"
#include "slam/measurements/imu_sample.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// An IMU recorded beside the cameras (EuRoC's imu0).
struct InertialStream {
  std::vector<ImuSample> samples;  // in time order
  // The rectified left camera's optical frame (the frames' camera) in the IMU frame.
  Eigen::Isometry3d T_imu_cam = Eigen::Isometry3d::Identity();
  std::string source;              // the file the samples came from
};

class DatasetReader {
 public:
  virtual ~DatasetReader() = default;

  // Fills `frame` with the next frame (every field reset; images rectified pinhole, RGB) and
  // returns true, or returns false after the last one. Stamps strictly increase. A frame whose
  // images cannot be read is an InputError naming the file, unless AllowSkippingBadFrames(true):
  // then it is skipped with a warning on stderr when earlier frames were read and the frame
  // before it was fine (FrameSkipPolicy).
  virtual bool Next(StereoFrame* frame) = 0;
  void AllowSkippingBadFrames(int max_skipped) { skip_.Allow(max_skipped); }
  // Frames skipped so far (unreadable images).
  int frames_skipped() const { return skip_.skipped(); }

  // Frames the dataset lists (after left/right and rgb/depth association), skipped ones included.
  virtual size_t NumFrames() const = 0;
  // Rectified pinhole intrinsics of the frames handed out (left camera; the right one is equal).
  virtual const PinholeIntrinsics& intrinsics() const = 0;
  // Right camera at +baseline along the left camera's x axis (m); 0 for RGB-D (no right image).
  virtual double baseline_m() const = 0;
  // Frames carry left_depth_m (metric depth along the optical axis, 0 = no depth).
  virtual bool HasDepth() const = 0;
  // Frames carry left_instance_id and instances.
  virtual bool HasSegmentation() const = 0;
  // Ground truth of the left camera's (rectified) optical frame in the world, TUM-like: its own
  // stamps, which need not match the frames'; nullopt when the dataset has none.
  virtual const std::optional<std::vector<StampedPose>>& ground_truth() const = 0;
  // Where the camera calibration came from (a file, or a published calibration), for the
  // record: printed and written to metrics.json.
  virtual const std::string& calibration_source() const = 0;
  // The dataset's IMU, when it has one (EuRoC imu0/data.csv); nullptr otherwise.
  virtual const InertialStream* inertial() const { return nullptr; }
  // The path length the dataset's own runs report (metrics.json path_length_m), when it defines
  // one: a viqu recording's is the trunk's path in the ground plane, frame to frame, as the live
  // run sums it. nullopt: the replay takes the ground-truth camera's 3-D path.
  virtual std::optional<double> path_length_m() const { return std::nullopt; }

 protected:
  FrameSkipPolicy skip_;  // what Next does with an unreadable frame
};

}  // namespace viqu::io

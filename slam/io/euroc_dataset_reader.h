#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/io/dataset_reader.h"
#include "slam/io/frame_skip_policy.h"
#include "slam/io/image_list.h"
#include "slam/io/instance_mask_folder.h"
#include "slam/io/stereo_rectifier.h"

namespace viqu::io {

// EuRoC MAV datasets (e.g. MH_01_easy): mav0/cam0 and mav0/cam1 (data.csv, data/*.png, grey
// 8-bit, sensor.yaml with the radial-tangential calibration and T_BS). Left and right images
// are paired by equal stamps (an image without partner is skipped with a warning), rectified
// (StereoRectifier) and handed out as RGB; intrinsics() and baseline_m() are the rectified ones.
//
// Ground truth, when mav0/state_groundtruth_estimate0/data.csv exists: the IMU pose T_w_imu
// composed with the camera extrinsics and the rectifying rotation,
//   T_w_rect0 = T_w_imu * T_B_imu^-1 * T_B_cam0 * R1^T,
// with T_B_imu from imu0/sensor.yaml (identity when absent; EuRoC's body frame is the IMU).
//
// With a masks folder (InstanceMaskFolder, docs/MASKS.md) frames carry left_instance_id and
// instances: the mask named like the cam0 image, in the raw cam0 geometry, goes through the
// left image's rectification by nearest neighbour.
//
// The IMU, when mav0/imu0/data.csv exists: its samples and the rectified left camera in the IMU
// frame, T_imu_rect0 = T_B_imu^-1 * T_B_cam0 * R1^T (inertial(); slam.mode full uses the gyro).
class EurocDatasetReader : public DatasetReader {
 public:
  // `dir`: the folder that holds mav0/, or mav0 itself; `masks_dir`: instance masks, "" for
  // none. Bad input: InputError naming the file.
  explicit EurocDatasetReader(const std::string& dir, const std::string& masks_dir = "");

  bool Next(StereoFrame* frame) override;
  size_t NumFrames() const override { return frames_.size(); }
  const PinholeIntrinsics& intrinsics() const override { return rectifier_->intrinsics(); }
  double baseline_m() const override { return rectifier_->baseline_m(); }
  bool HasDepth() const override { return false; }
  bool HasSegmentation() const override { return masks_.has_value(); }
  const std::optional<std::vector<StampedPose>>& ground_truth() const override { return ground_truth_; }
  const std::string& calibration_source() const override { return calibration_source_; }
  const InertialStream* inertial() const override { return inertial_ ? &*inertial_ : nullptr; }

 private:
  std::vector<ImagePair> frames_;               // cam0 (a) / cam1 (b) image files
  size_t next_ = 0;                             // index of the next frame
  std::string calibration_source_;              // cam0 and cam1 sensor.yaml
  PinholeIntrinsics raw_;                       // calibrated (raw) image size, for checks
  std::unique_ptr<StereoRectifier> rectifier_;
  std::optional<InstanceMaskFolder> masks_;     // --masks
  std::optional<std::vector<StampedPose>> ground_truth_;  // rectified left camera in world
  std::optional<InertialStream> inertial_;     // imu0
};

}  // namespace viqu::io

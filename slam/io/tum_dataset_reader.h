#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/io/dataset_reader.h"
#include "slam/io/frame_skip_policy.h"
#include "slam/io/image_list.h"
#include "slam/io/image_undistorter.h"
#include "slam/io/instance_mask_folder.h"
#include "slam/io/tum_camera.h"

namespace viqu::io {

// Pairs farther apart than this are not associated (s), as associate.py's default.
constexpr double kTumMaxRgbDepthDiffS = 0.02;

// TUM RGB-D sequences (also written by sim/tum_recorder): rgb.txt and depth.txt ("t_s file",
// '#' comments), 8-bit colour images, 16-bit depth PNG (value / depth_scale = metres, 0 = no
// depth), optional groundtruth.txt (the colour camera's optical centre in the world, TUM
// format). Each colour image is paired with the depth image nearest in time within 0.02 s, as
// TUM's associate.py does; colour images without depth are skipped with a warning. The camera
// comes from ReadTumCamera; distorted sequences (freiburg1/2) are undistorted on reading.
// Frames carry left_rgb and left_depth_m; right_rgb stays empty and baseline_m() is 0.
// With a masks folder (InstanceMaskFolder, docs/MASKS.md) they also carry left_instance_id and
// instances: the mask named like the rgb image, undistorted with it by nearest neighbour.
class TumDatasetReader : public DatasetReader {
 public:
  // `masks_dir`: instance masks, "" for none. Bad input: InputError naming the file.
  // `camera_file`: a calibration (ReadCameraFile) instead of the folder's own; "" for that.
  explicit TumDatasetReader(const std::string& dir, const std::string& masks_dir = "", const std::string& camera_file = "");

  bool Next(StereoFrame* frame) override;
  size_t NumFrames() const override { return frames_.size(); }
  const PinholeIntrinsics& intrinsics() const override { return camera_.calibration.pinhole; }
  double baseline_m() const override { return 0; }
  bool HasDepth() const override { return true; }
  bool HasSegmentation() const override { return masks_.has_value(); }
  const std::optional<std::vector<StampedPose>>& ground_truth() const override { return ground_truth_; }

  // Where the intrinsics came from (--camera, camera.yaml, or which TUM calibration).
  const std::string& camera_source() const { return camera_.source; }
  const std::string& calibration_source() const override { return camera_.source; }

 private:
  // Reads one frame; false (with *why) when an image cannot be read.
  bool ReadFrame(const ImagePair& files, StereoFrame* frame, std::string* why) const;

  TumCamera camera_;
  std::unique_ptr<ImageUndistorter> undistorter_;  // null when the images have no distortion
  std::optional<InstanceMaskFolder> masks_;        // --masks
  std::vector<ImagePair> frames_;                  // rgb (a) / depth (b) image files
  size_t next_ = 0;                                // index of the next frame
  std::optional<std::vector<StampedPose>> ground_truth_;
};

}  // namespace viqu::io

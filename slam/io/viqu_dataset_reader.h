#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slam/io/dataset_reader.h"
#include "slam/io/frame_skip_policy.h"
#include "slam/io/image_list.h"
#include "slam/io/instance_mask_folder.h"

namespace viqu::io {

// Recordings of `viqu run --record` (sim/euroc_recorder): RUN/dataset/mav0/... or the dataset
// folder itself. The images are rectified pinhole RGB already: intrinsics come from
// cam0/sensor.yaml, the baseline from the cam0/cam1 T_BS (a recording that is not a rectified
// pair is rejected: read it with --format euroc). depth0 (16-bit, depth_unit_m from its
// sensor.yaml, default 1 mm) and seg0 (16-bit instance ids, instances.csv) are read when
// present; a frame lacks them when their data.csv has no row with its stamp. A frame's
// `instances` are its rows of seg0/frame_instances.csv (the live frame's list, per-frame
// categories included; in order of id) when the recording has that file, else the rows of
// seg0/instances.csv whose ids occur in its image (recordings made before frame_instances.csv
// existed). A masks folder (InstanceMaskFolder, docs/MASKS.md; masks named like the cam0 images)
// replaces seg0.
//
// Ground truth of the left camera: RUN/trajectory_gt.txt when the run folder was given and has
// it; otherwise mav0/state_groundtruth_estimate0 (trunk pose T_w_body) composed with cam0's
// T_BS: T_w_cam0 = T_w_body * T_body_cam0. Neither (or no rows): nullopt.
class ViquDatasetReader : public DatasetReader {
 public:
  // `masks_dir`: instance masks that replace seg0, "" for none. Bad input: InputError naming
  // the file.
  explicit ViquDatasetReader(const std::string& dir, const std::string& masks_dir = "");

  bool Next(StereoFrame* frame) override;
  size_t NumFrames() const override { return frames_.size(); }
  const PinholeIntrinsics& intrinsics() const override { return intrinsics_; }
  double baseline_m() const override { return baseline_m_; }
  bool HasDepth() const override { return has_depth_; }
  bool HasSegmentation() const override { return has_segmentation_; }
  const std::optional<std::vector<StampedPose>>& ground_truth() const override { return ground_truth_; }
  std::optional<double> path_length_m() const override { return path_length_m_; }
  const std::string& calibration_source() const override { return calibration_source_; }

 private:
  // Reads the images of one frame; false (with *why) when one cannot be read.
  bool ReadFrame(const ImagePair& files, StereoFrame* frame, std::string* why) const;

  std::vector<ImagePair> frames_;               // cam0 (a) / cam1 (b) image files
  size_t next_ = 0;                             // index of the next frame
  PinholeIntrinsics intrinsics_;
  std::string calibration_source_;              // cam0 and cam1 sensor.yaml
  double baseline_m_ = 0;
  bool has_depth_ = false, has_segmentation_ = false;
  std::map<int64_t, std::string> depth_files_;  // stamp (ns) -> depth0 image
  std::map<int64_t, std::string> seg_files_;    // stamp (ns) -> seg0 image
  double depth_unit_m_ = 0.001;                 // depth0 PNG value -> metres
  std::vector<SegmentInstance> instances_;      // seg0/instances.csv
  // seg0/frame_instances.csv by stamp (ns), when the recording has it.
  std::optional<std::map<int64_t, std::vector<SegmentInstance>>> frame_instances_;
  std::string frame_instances_path_;            // that file
  std::optional<InstanceMaskFolder> masks_;     // --masks (then seg0 is not read)
  std::optional<std::vector<StampedPose>> ground_truth_;  // left camera in world
  std::optional<double> path_length_m_;  // the trunk's, in the ground plane (state_groundtruth_estimate0)
};

}  // namespace viqu::io

#include "slam/io/euroc_dataset_reader.h"

#include <cstdio>
#include <filesystem>

#include "common/errors.h"
#include "slam/io/euroc_ground_truth.h"
#include "slam/io/euroc_layout.h"
#include "slam/io/image_files.h"
#include "slam/io/imu_csv.h"
#include "slam/io/pose_conversions.h"
#include "slam/io/segment_instances.h"

namespace viqu::io {

namespace fs = std::filesystem;

EurocDatasetReader::EurocDatasetReader(const std::string& dir, const std::string& masks_dir) {
  const EurocStereoLayout layout = ReadEurocStereoLayout(FindMav0(dir));
  frames_ = layout.frames;
  raw_ = layout.cam0.calibration.pinhole;
  calibration_source_ = (fs::path(layout.mav0) / "cam0" / "sensor.yaml").string() + " and cam1/sensor.yaml";
  const Eigen::Isometry3d T_cam0_cam1 = layout.cam0.T_B_S.inverse() * layout.cam1.T_B_S;
  rectifier_ = std::make_unique<StereoRectifier>(layout.cam0.calibration, layout.cam1.calibration, T_cam0_cam1,
                                                 (fs::path(layout.mav0) / "cam1" / "sensor.yaml").string());
  if (!masks_dir.empty()) masks_.emplace(masks_dir);

  std::error_code ec;
  const fs::path imu_yaml = fs::path(layout.mav0) / "imu0" / "sensor.yaml";
  const Eigen::Isometry3d T_B_imu = fs::exists(imu_yaml, ec) ? ReadEurocSensorTransform(imu_yaml.string())
                                                             : Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d T_imu_rect0 = T_B_imu.inverse() * layout.cam0.T_B_S * rectifier_->T_cam0_rect0();
  const fs::path gt_csv = fs::path(layout.mav0) / "state_groundtruth_estimate0" / "data.csv";
  if (fs::exists(gt_csv, ec)) {
    const std::vector<StampedPose> T_w_imu = ReadEurocGroundTruth(gt_csv.string());
    if (T_w_imu.empty()) {
      std::fprintf(stderr, "viqu: warning: %s lists no poses; no ground truth\n", gt_csv.c_str());
    } else {
      ground_truth_ = ChangeTrajectoryFrame(T_w_imu, T_imu_rect0);
    }
  }
  const fs::path imu_csv = fs::path(layout.mav0) / "imu0" / "data.csv";
  if (fs::exists(imu_csv, ec)) {
    inertial_.emplace();
    inertial_->samples = ReadImuCsv(imu_csv.string());
    inertial_->T_imu_cam = T_imu_rect0;
    inertial_->source = imu_csv.string();
  }
}

bool EurocDatasetReader::Next(StereoFrame* frame) {
  while (next_ < frames_.size()) {
    const ImagePair& files = frames_[next_++];
    std::string why;
    const cv::Mat raw0 = ReadImage8(files.a, &why);
    const cv::Mat raw1 = raw0.empty() ? cv::Mat() : ReadImage8(files.b, &why);
    if (raw0.empty() || raw1.empty()) {
      skip_.Bad(why);
      continue;
    }
    for (const auto& [image, path] : {std::pair{&raw0, &files.a}, std::pair{&raw1, &files.b}}) {
      if (image->cols != raw_.width || image->rows != raw_.height) {
        throw InputError(*path + ": image is " + std::to_string(image->cols) + "x" + std::to_string(image->rows) +
                         ", the calibration says " + std::to_string(raw_.width) + "x" + std::to_string(raw_.height));
      }
    }
    // Rectify the stored image (grey for EuRoC), then expand to RGB: a third of the remap work.
    cv::Mat rect0, rect1;
    rectifier_->Rectify(raw0, raw1, &rect0, &rect1);
    *frame = StereoFrame();
    frame->t_ns = files.t_ns;
    frame->left_rgb = ToRgb(rect0);
    frame->right_rgb = ToRgb(rect1);
    frame->intrinsics = rectifier_->intrinsics();
    frame->baseline_m = rectifier_->baseline_m();
    if (masks_) {
      const cv::Mat raw_ids = masks_->Read(files.a, cv::Size(raw_.width, raw_.height));
      frame->left_instance_id = rectifier_->RectifyLeftLabels(raw_ids);
      frame->instances = InstancesPresent(frame->left_instance_id, masks_->instances());
    }
    skip_.Good();
    return true;
  }
  return false;
}

}  // namespace viqu::io

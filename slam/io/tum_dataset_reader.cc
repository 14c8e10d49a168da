#include "slam/io/tum_dataset_reader.h"

#include <filesystem>
#include <utility>

#include "common/errors.h"
#include "slam/eval/trajectory.h"
#include "slam/io/camera_file.h"
#include "slam/io/image_files.h"
#include "slam/io/segment_instances.h"

namespace viqu::io {

namespace fs = std::filesystem;

TumDatasetReader::TumDatasetReader(const std::string& dir, const std::string& masks_dir, const std::string& camera_file) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": dataset folder not found");
  const fs::path d(dir);
  const std::string rgb_txt = (d / "rgb.txt").string(), depth_txt = (d / "depth.txt").string();
  const std::vector<ImageEntry> rgb = ReadTumImageList(rgb_txt, dir);
  const std::vector<ImageEntry> depth = ReadTumImageList(depth_txt, dir);
  if (rgb.empty()) throw InputError(rgb_txt + ": no images listed (empty dataset)");
  if (depth.empty()) throw InputError(depth_txt + ": no images listed (empty dataset)");
  frames_ = PairNearestStamps(rgb, depth, kTumMaxRgbDepthDiffS, rgb_txt, depth_txt);
  if (frames_.empty()) {
    throw InputError(rgb_txt + ": no colour image has a depth image in " + depth_txt + " within 0.02 s");
  }
  // The calibration after the lists: a folder that is no TUM sequence says so first.
  camera_ = camera_file.empty() ? ReadTumCamera(dir) : ReadCameraFile(camera_file);
  // The first image's size: taken for a calibration without one (older ORB-SLAM2 files), else
  // checked against it, so that a calibration of another camera is named before any work.
  PinholeIntrinsics& k = camera_.calibration.pinhole;
  {
    std::string why;
    const cv::Mat first = ReadImage8(frames_.front().a, &why);
    if (first.empty()) throw InputError(why);
    if (k.width == 0) {
      k.width = first.cols;
      k.height = first.rows;
    } else if (first.cols != k.width || first.rows != k.height) {
      throw InputError(camera_.source + ": the calibration is for " + std::to_string(k.width) + "x" +
                       std::to_string(k.height) + " images, " + frames_.front().a + " is " + std::to_string(first.cols) +
                       "x" + std::to_string(first.rows));
    }
  }
  CheckCalibration(camera_.calibration, camera_.keys, camera_.source);
  if (!HasNoDistortion(camera_.calibration)) undistorter_ = std::make_unique<ImageUndistorter>(camera_.calibration);
  if (!masks_dir.empty()) masks_.emplace(masks_dir);
  const fs::path gt = d / "groundtruth.txt";
  if (fs::exists(gt, ec)) ground_truth_ = eval::ReadTumTrajectory(gt.string());
}

bool TumDatasetReader::ReadFrame(const ImagePair& files, StereoFrame* frame, std::string* why) const {
  const PinholeIntrinsics& k = camera_.calibration.pinhole;
  cv::Mat rgb = ReadImage8(files.a, why);
  if (rgb.empty()) return false;
  cv::Mat depth = ReadImage16(files.b, why);
  if (depth.empty()) return false;
  for (const auto& [image, path] : {std::pair{&rgb, &files.a}, std::pair{&depth, &files.b}}) {
    if (image->cols != k.width || image->rows != k.height) {
      throw InputError(*path + ": image is " + std::to_string(image->cols) + "x" + std::to_string(image->rows) +
                       ", the camera (" + camera_.source + ") is " + std::to_string(k.width) + "x" +
                       std::to_string(k.height));
    }
  }
  if (undistorter_) {
    rgb = undistorter_->Colour(rgb);
    depth = undistorter_->Depth(depth);
  }
  *frame = StereoFrame();
  frame->t_ns = files.t_ns;
  frame->left_rgb = ToRgb(rgb);
  frame->left_depth_m = DepthToMetres(depth, 1.0 / camera_.depth_scale);
  frame->intrinsics = k;
  frame->baseline_m = 0;
  if (masks_) {
    const cv::Mat raw_ids = masks_->Read(files.a, cv::Size(k.width, k.height));
    frame->left_instance_id = undistorter_ ? undistorter_->Depth(raw_ids) : raw_ids;
    frame->instances = InstancesPresent(frame->left_instance_id, masks_->instances());
  }
  return true;
}

bool TumDatasetReader::Next(StereoFrame* frame) {
  return NextReadable(frames_, &next_, &skip_, frame, [this](const ImagePair& files, StereoFrame* f, std::string* why) {
    return ReadFrame(files, f, why);
  });
}

}  // namespace viqu::io

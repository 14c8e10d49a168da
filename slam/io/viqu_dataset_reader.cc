#include "slam/io/viqu_dataset_reader.h"

#include <cmath>
#include <filesystem>
#include <utility>

#include "common/errors.h"
#include "common/yaml_map_reader.h"
#include "slam/eval/trajectory.h"
#include "slam/io/euroc_ground_truth.h"
#include "slam/io/euroc_layout.h"
#include "slam/io/euroc_sensor_yaml.h"
#include "slam/io/image_files.h"
#include "slam/io/pose_conversions.h"
#include "slam/io/segment_instances.h"

namespace viqu::io {
namespace {

// A 16-bit single-channel image (depth0, seg0) larger than any PNG of its size can honestly be
// (MaxMaskFileBytes) is a broken recording, not a frame to decode: 200 MB behind a 640x480
// header was accepted.
void RequireSized16(const std::string& path, const cv::Size& size, const char* what) {
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > MaxMaskFileBytes(size)) {
    throw InputError(path + ": " + std::to_string(bytes >> 20) + " MiB, too large for a " + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + " 16-bit " + what + " (at most " +
                     std::to_string(MaxMaskFileBytes(size) >> 10) + " KiB)");
  }
}

namespace fs = std::filesystem;

// Tolerances for "already rectified": the recorder prints T_BS with 12 significant digits.
constexpr double kMaxRotationRad = 1e-6;
constexpr double kMaxOffAxisM = 1e-6;

std::map<int64_t, std::string> ImageMap(const fs::path& folder) {
  std::map<int64_t, std::string> out;
  for (ImageEntry& e : ReadEurocImageList((folder / "data.csv").string(), (folder / "data").string())) {
    out.emplace(e.t_ns, std::move(e.path));
  }
  return out;
}

double ReadDepthUnit(const fs::path& yaml) {
  std::error_code ec;
  if (!fs::exists(yaml, ec)) return 0.001;
  const YamlSource src(yaml.string());
  YamlMapReader top(src, LoadEurocYaml(yaml.string()), "");
  double unit = 0.001;
  top.Number("depth_unit_m", &unit, NumberRange::Positive());
  return unit;
}

}  // namespace

ViquDatasetReader::ViquDatasetReader(const std::string& dir, const std::string& masks_dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": dataset folder not found");
  // A run folder holds dataset/mav0 and trajectory_gt.txt; a dataset folder holds mav0.
  const fs::path d(dir);
  std::string run_dir;
  fs::path dataset = d;
  if (fs::is_directory(d / "dataset" / "mav0", ec)) {
    run_dir = d.string();
    dataset = d / "dataset";
  } else if (!fs::is_directory(d / "mav0", ec)) {
    // A TUM RGB-D folder (the same run's --record-tum, or a public sequence) is told apart.
    const std::string hint = fs::exists(d / "rgb.txt", ec) ? "; it holds rgb.txt: a TUM RGB-D folder? (--format tum)" : "";
    throw InputError(dir + ": not a viqu recording (expected DIR/dataset/mav0 or DIR/mav0, written by "
                     "`viqu run --record`)" + hint);
  }
  const EurocStereoLayout layout = ReadEurocStereoLayout((dataset / "mav0").string());
  const fs::path mav0(layout.mav0);
  calibration_source_ = (mav0 / "cam0" / "sensor.yaml").string() + " and cam1/sensor.yaml";
  frames_ = layout.frames;

  // The recorder writes rectified images: equal pinhole intrinsics, no distortion, cam1 at +x.
  const std::string cam1_yaml = (mav0 / "cam1" / "sensor.yaml").string();
  const PinholeIntrinsics& k0 = layout.cam0.calibration.pinhole;
  const PinholeIntrinsics& k1 = layout.cam1.calibration.pinhole;
  const Eigen::Isometry3d T_cam0_cam1 = layout.cam0.T_B_S.inverse() * layout.cam1.T_B_S;
  const Eigen::Vector3d t = T_cam0_cam1.translation();
  const double angle = Eigen::AngleAxisd(T_cam0_cam1.linear()).angle();
  const bool rectified = k0.width == k1.width && k0.height == k1.height && k0.fx == k1.fx && k0.fy == k1.fy &&
                         k0.cx == k1.cx && k0.cy == k1.cy && HasNoDistortion(layout.cam0.calibration) &&
                         HasNoDistortion(layout.cam1.calibration) && angle < kMaxRotationRad &&
                         std::abs(t.y()) < kMaxOffAxisM && std::abs(t.z()) < kMaxOffAxisM && t.x() > 0;
  if (!rectified) {
    throw InputError(cam1_yaml + ": cam0/cam1 are not a rectified pair (equal pinhole intrinsics, no distortion, "
                     "cam1 displaced along +x of cam0 only); read this dataset with --format euroc");
  }
  intrinsics_ = k0;
  baseline_m_ = t.x();

  if (fs::is_directory(mav0 / "depth0", ec)) {
    has_depth_ = true;
    depth_files_ = ImageMap(mav0 / "depth0");
    depth_unit_m_ = ReadDepthUnit(mav0 / "depth0" / "sensor.yaml");
  }
  if (!masks_dir.empty()) {
    masks_.emplace(masks_dir);
    has_segmentation_ = true;
  } else if (fs::is_directory(mav0 / "seg0", ec)) {
    has_segmentation_ = true;
    seg_files_ = ImageMap(mav0 / "seg0");
    const fs::path instances = mav0 / "seg0" / "instances.csv";
    if (fs::exists(instances, ec)) instances_ = ReadSegmentInstances(instances.string());
    const fs::path per_frame = mav0 / "seg0" / "frame_instances.csv";
    if (fs::exists(per_frame, ec)) {
      frame_instances_path_ = per_frame.string();
      frame_instances_ = ReadFrameInstances(frame_instances_path_);
    }
  }

  const fs::path gt_tum = fs::path(run_dir) / "trajectory_gt.txt";
  const fs::path gt_body = mav0 / "state_groundtruth_estimate0" / "data.csv";
  std::vector<StampedPose> T_w_body;
  if (fs::exists(gt_body, ec)) T_w_body = ReadEurocGroundTruth(gt_body.string());
  if (!run_dir.empty() && fs::exists(gt_tum, ec)) {
    ground_truth_ = eval::ReadTumTrajectory(gt_tum.string());
  } else if (!T_w_body.empty()) {
    ground_truth_ = ChangeTrajectoryFrame(T_w_body, layout.cam0.T_B_S);
  }
  if (!T_w_body.empty()) {
    // The live run's path_length_m (runner/run_scenario.cc): the trunk in the ground plane, summed
    // over the frames (the recording holds the trunk's pose at every frame).
    double length = 0;
    for (size_t i = 1; i < T_w_body.size(); ++i) length += (T_w_body[i].p_w_x - T_w_body[i - 1].p_w_x).head<2>().norm();
    path_length_m_ = length;
  }
}

bool ViquDatasetReader::ReadFrame(const ImagePair& files, StereoFrame* frame, std::string* why) const {
  const cv::Mat left = ReadImage8(files.a, why);
  if (left.empty()) return false;
  const cv::Mat right = ReadImage8(files.b, why);
  if (right.empty()) return false;
  for (const auto& [image, path] : {std::pair{&left, &files.a}, std::pair{&right, &files.b}}) {
    if (image->cols != intrinsics_.width || image->rows != intrinsics_.height) {
      throw InputError(*path + ": image is " + std::to_string(image->cols) + "x" + std::to_string(image->rows) +
                       ", sensor.yaml says " + std::to_string(intrinsics_.width) + "x" +
                       std::to_string(intrinsics_.height));
    }
  }
  *frame = StereoFrame();
  frame->t_ns = files.t_ns;
  frame->left_rgb = ToRgb(left);
  frame->right_rgb = ToRgb(right);
  frame->intrinsics = intrinsics_;
  frame->baseline_m = baseline_m_;
  const cv::Size size(intrinsics_.width, intrinsics_.height);
  if (const auto it = depth_files_.find(files.t_ns); it != depth_files_.end()) {
    RequireSized16(it->second, size, "depth image");
    const cv::Mat depth = ReadImage16(it->second, why);
    if (depth.empty()) return false;
    if (depth.size() != size) throw InputError(it->second + ": depth image size differs from the camera's");
    frame->left_depth_m = DepthToMetres(depth, depth_unit_m_);
  }
  if (masks_) {
    frame->left_instance_id = masks_->Read(files.a, size);
    frame->instances = InstancesPresent(frame->left_instance_id, masks_->instances());
  } else if (const auto it = seg_files_.find(files.t_ns); it != seg_files_.end()) {
    RequireSized16(it->second, size, "segmentation image");
    frame->left_instance_id = ReadImage16(it->second, why);
    if (frame->left_instance_id.empty()) return false;
    if (frame->left_instance_id.size() != size) {
      throw InputError(it->second + ": segmentation image size differs from the camera's");
    }
    if (frame_instances_) {
      const auto listed = frame_instances_->find(files.t_ns);
      if (listed != frame_instances_->end()) frame->instances = listed->second;
      CheckIdsListed(frame->left_instance_id, frame->instances, it->second,
                     "for its stamp in " + frame_instances_path_);
    } else {
      frame->instances = InstancesPresent(frame->left_instance_id, instances_);
    }
  }
  return true;
}

bool ViquDatasetReader::Next(StereoFrame* frame) {
  return NextReadable(frames_, &next_, &skip_, frame, [this](const ImagePair& files, StereoFrame* f, std::string* why) {
    return ReadFrame(files, f, why);
  });
}

}  // namespace viqu::io

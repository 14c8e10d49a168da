#include "sim/tum_recorder.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "sim/depth_quantisation.h"

namespace viqu::sim {
namespace {

namespace fs = std::filesystem;

std::string Fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.17g", v);  // round-trips every double
  return buf;
}

}  // namespace

TumRecorder::TumRecorder(const std::string& dataset_dir, const PinholeIntrinsics& intrinsics)
    : final_dir_(fs::path(dataset_dir).lexically_normal().string()),
      partial_dir_(final_dir_ + ".partial"),
      intrinsics_(intrinsics) {
  std::error_code ec;
  fs::remove_all(partial_dir_, ec);
  if (ec) throw RunError("cannot remove stale " + partial_dir_ + ": " + ec.message());
  for (const char* sub : {"rgb", "depth"}) {
    fs::create_directories(fs::path(partial_dir_) / sub, ec);
    if (ec) throw RunError("cannot create " + partial_dir_ + "/" + sub + ": " + ec.message());
  }
  rgb_.file = std::make_unique<AtomicOutputFile>(partial_dir_ + "/rgb.txt");
  rgb_.file->Write("# color images\n# file: viqu simulation, left camera\n# timestamp filename\n");
  depth_.file = std::make_unique<AtomicOutputFile>(partial_dir_ + "/depth.txt");
  depth_.file->Write("# depth maps\n# file: viqu simulation, left camera\n# timestamp filename\n");
  groundtruth_ = std::make_unique<TrajectoryWriter>(partial_dir_ + "/groundtruth.txt");
}

TumRecorder::~TumRecorder() {
  if (finished_) return;
  writer_.reset();  // stop writing images into the folder that is about to go
  rgb_.file.reset();
  depth_.file.reset();
  groundtruth_.reset();
  std::error_code ec;
  fs::remove_all(partial_dir_, ec);
}

void TumRecorder::WriteImage(const char* folder, ListStream* list, int64_t t_ns, const cv::Mat& image,
                             PngContent content) {
  if (finished_) throw RunError(std::string("TumRecorder: ") + folder + " image added after Finish()");
  if (t_ns <= list->last_t_ns) {
    throw RunError(std::string("TumRecorder: ") + folder + " timestamp " + std::to_string(t_ns) +
                   " ns does not follow " + std::to_string(list->last_t_ns) + " ns");
  }
  list->last_t_ns = t_ns;
  const std::string name = std::string(folder) + "/" + FormatSeconds(t_ns) + ".png";
  writer_->Push(partial_dir_ + "/" + name, image, content);  // `image` is not reused by the caller
  list->file->Write(FormatSeconds(t_ns) + " " + name + "\n");
}

void TumRecorder::AddFrame(const StereoFrame& frame, const cv::Mat& depth_steps) {
  if (frame.left_rgb.type() != CV_8UC3) throw RunError("TumRecorder: the left image must be CV_8UC3 (RGB)");
  WriteImage("rgb", &rgb_, frame.t_ns, frame.left_rgb.clone(), PngContent::kPhoto);  // the caller reuses its buffer
  if (frame.left_depth_m.empty()) return;
  WriteImage("depth", &depth_, frame.t_ns, DepthStepsToWrite(frame.left_depth_m, depth_steps, kDepthScale, "TumRecorder"),
             PngContent::kFlat);
}

void TumRecorder::AddGroundTruth(const GroundTruthState& state) {
  if (finished_) throw RunError("TumRecorder: ground truth added after Finish()");
  if (state.t_ns <= last_gt_t_ns_) {
    throw RunError("TumRecorder: ground truth timestamp " + std::to_string(state.t_ns) + " ns does not follow " +
                   std::to_string(last_gt_t_ns_) + " ns");
  }
  last_gt_t_ns_ = state.t_ns;
  StampedPose pose = state.T_w_cam;
  pose.t_ns = state.t_ns;
  groundtruth_->Add(pose);
}

void TumRecorder::Finish() {
  if (finished_) return;
  writer_->Drain();
  const PinholeIntrinsics& k = intrinsics_;
  WriteFileAtomic(partial_dir_ + "/camera.yaml",
                  "# viqu TUM RGB-D recording: pinhole intrinsics of rgb/ and depth/ (px, pixel centres at\n"
                  "# integer coordinates); depth PNG value / depth_scale = depth along the optical axis (m).\n"
                  "fx: " + Fmt(k.fx) + "\nfy: " + Fmt(k.fy) + "\ncx: " + Fmt(k.cx) + "\ncy: " + Fmt(k.cy) +
                      "\nwidth: " + std::to_string(k.width) + "\nheight: " + std::to_string(k.height) +
                      "\ndepth_scale: " + Fmt(kDepthScale) + "\n");
  rgb_.file->Commit();
  depth_.file->Commit();
  groundtruth_->Close();
  // Swap the finished folder into place; an old dataset under the final name is replaced.
  CommitTempDirectory(partial_dir_, final_dir_);
  finished_ = true;
}

}  // namespace viqu::sim

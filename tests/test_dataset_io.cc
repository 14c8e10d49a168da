// Dataset input/output for offline SLAM: the viqu recording (sim::EurocRecorder) and TUM RGB-D
// (sim::TumRecorder) read back exactly, EuRoC MAV rectification checked on known 3D points, and
// bad input reported as InputError naming the file (a single corrupt image skipped); instance
// masks of an external detector (--masks) through each reader.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"
#include "common/run_folder.h"
#include "sim/depth_quantisation.h"
#include "sim/euroc_recorder.h"
#include "sim/trajectory_writer.h"
#include "sim/tum_recorder.h"
#include "slam/io/euroc_dataset_reader.h"
#include "slam/io/open_dataset.h"
#include "slam/io/pose_conversions.h"
#include "slam/io/calibration_check.h"
#include "slam/io/camera_file.h"
#include "slam/io/tum_dataset_reader.h"
#include "slam/io/viqu_dataset_reader.h"

namespace viqu::io {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Helpers

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "viqu_dataset_io_XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void WriteText(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << p;
}

std::string ReadAllText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Expects `f` to throw InputError whose message contains every one of `parts`.
template <typename F>
void ExpectInputError(F f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

cv::Mat RandomRgb(int w, int h, uint64_t seed) {
  cv::Mat m(h, w, CV_8UC3);
  cv::RNG(seed).fill(m, cv::RNG::UNIFORM, 0, 256);
  return m;
}

// Depth in [0.3, 10) m with a few pixels of no depth (0).
cv::Mat RandomDepth(int w, int h, uint64_t seed) {
  cv::Mat m(h, w, CV_32F);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0.3, 10.0);
  for (int i = 0; i < 5; ++i) m.at<float>(rng.uniform(0, h), rng.uniform(0, w)) = 0.0f;
  return m;
}

Eigen::Isometry3d Pose(double yaw, double pitch, double roll, const Eigen::Vector3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = p;
  return T;
}

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

double MaxAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return std::numeric_limits<double>::infinity();
  return cv::norm(a, b, cv::NORM_INF);
}

// The body-mounted camera rig of the viqu recordings: optical frame looking along body x.
Eigen::Isometry3d CameraInBody() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.1, 0.02, 0.03);
  return T;
}

// ---------------------------------------------------------------------------------------------
// viqu format: written by sim::EurocRecorder, read by ViquDatasetReader

constexpr int kW = 32, kH = 24;

struct ViquRecording {
  std::vector<StereoFrame> frames;
  std::vector<GroundTruthState> gt;
  sim::EurocRig rig;
};

ViquRecording RecordViqu(const fs::path& final_dir, int num_frames) {
  // Written as a run writes its folder: complete, with its marker (common/run_folder.h).
  RunFolderWriter folder(final_dir.string(), false, "RecordViqu");
  const fs::path run_dir = folder.path();
  ViquRecording rec;
  rec.rig.camera.width = kW;
  rec.rig.camera.height = kH;
  rec.rig.intrinsics = {kW, kH, 30.5, 29.25, 15.5, 11.75};
  rec.rig.T_body_cam0 = CameraInBody();
  rec.rig.T_body_cam1 = rec.rig.T_body_cam0 * Eigen::Translation3d(0.04, 0, 0);
  sim::EurocRecorder recorder((run_dir / "dataset").string(), rec.rig);
  sim::TrajectoryWriter gt_file((run_dir / "trajectory_gt.txt").string());
  for (int i = 0; i < num_frames; ++i) {
    StereoFrame f;
    f.t_ns = 1000000000LL + i * 50000000LL;
    f.left_rgb = RandomRgb(kW, kH, 10 + i);
    f.right_rgb = RandomRgb(kW, kH, 100 + i);
    f.left_depth_m = RandomDepth(kW, kH, 200 + i);
    f.left_instance_id = cv::Mat(kH, kW, CV_16U, cv::Scalar(0));
    f.left_instance_id(cv::Rect(2, 3, 5, 4)).setTo(300);
    f.instances = {{0, Category::kBackground, "background"}, {300, Category::kPerson, "person:alice"}};
    if (i != 1) {  // the box is out of view in frame 1
      f.left_instance_id(cv::Rect(20, 10, 3, 3)).setTo(7);
      f.instances.push_back({7, Category::kBox, "box_1,big"});
    }
    GroundTruthState g;
    g.t_ns = f.t_ns;
    const Eigen::Isometry3d T_w_body = Pose(0.3 * i, 0.05, -0.02 * i, Eigen::Vector3d(0.1 * i, 2.0 - 0.05 * i, 0.07));
    g.T_w_body = ToStampedPose(g.t_ns, T_w_body);
    g.T_w_cam = ToStampedPose(g.t_ns, T_w_body * rec.rig.T_body_cam0);
    recorder.AddFrame(f);
    recorder.AddGroundTruth(g);
    gt_file.Add(g.T_w_cam);
    rec.frames.push_back(f);
    rec.gt.push_back(g);
  }
  recorder.Finish();
  gt_file.Close();
  folder.Complete(0);
  return rec;
}

void ExpectSameFrames(DatasetReader* reader, const ViquRecording& rec) {
  ASSERT_EQ(reader->NumFrames(), rec.frames.size());
  StereoFrame f;
  for (const StereoFrame& want : rec.frames) {
    ASSERT_TRUE(reader->Next(&f));
    EXPECT_EQ(f.t_ns, want.t_ns);
    EXPECT_EQ(MaxAbsDiff(f.left_rgb, want.left_rgb), 0.0);
    EXPECT_EQ(MaxAbsDiff(f.right_rgb, want.right_rgb), 0.0);
    ASSERT_EQ(f.left_depth_m.type(), CV_32F);
    ASSERT_EQ(f.left_depth_m.size(), want.left_depth_m.size());
    double worst = 0;
    for (int r = 0; r < kH; ++r) {
      for (int c = 0; c < kW; ++c) {
        const float w = want.left_depth_m.at<float>(r, c), got = f.left_depth_m.at<float>(r, c);
        if (w == 0.0f) {
          EXPECT_EQ(got, 0.0f);
        } else {
          worst = std::max(worst, std::abs(static_cast<double>(got) - w));
        }
      }
    }
    EXPECT_LE(worst, 0.0001 + 1e-6);  // PNG in steps of 1/5000 m: half a step
    EXPECT_EQ(MaxAbsDiff(f.left_instance_id, want.left_instance_id), 0.0);
    ASSERT_EQ(f.instances.size(), want.instances.size());
    std::vector<SegmentInstance> sorted = want.instances;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    for (size_t i = 0; i < sorted.size(); ++i) {
      EXPECT_EQ(f.instances[i].id, sorted[i].id);
      EXPECT_EQ(f.instances[i].category, sorted[i].category);
      EXPECT_EQ(f.instances[i].name, sorted[i].name);
    }
    EXPECT_EQ(f.intrinsics.fx, rec.rig.intrinsics.fx);
    EXPECT_NEAR(f.baseline_m, 0.04, 1e-9);
  }
  EXPECT_FALSE(reader->Next(&f));
  EXPECT_FALSE(reader->Next(&f));
}

void ExpectGroundTruth(const DatasetReader& reader, const std::vector<GroundTruthState>& want, double tol) {
  ASSERT_TRUE(reader.ground_truth().has_value());
  const std::vector<StampedPose>& gt = *reader.ground_truth();
  ASSERT_EQ(gt.size(), want.size());
  for (size_t i = 0; i < gt.size(); ++i) {
    EXPECT_EQ(gt[i].t_ns, want[i].t_ns);
    EXPECT_LT((gt[i].p_w_x - want[i].T_w_cam.p_w_x).norm(), tol) << i;
    EXPECT_LT(AngleBetween(gt[i].q_w_x, want[i].T_w_cam.q_w_x), tol) << i;
  }
}

TEST(ViquDatasetReader, ReadsARunFolderBackExactly) {
  TempDir tmp;
  const ViquRecording rec = RecordViqu(tmp.path() / "run", 4);
  const std::unique_ptr<DatasetReader> reader = OpenDataset((tmp.path() / "run").string(), DatasetFormat::kViqu);
  const PinholeIntrinsics& k = reader->intrinsics();
  EXPECT_EQ(k.width, kW);
  EXPECT_EQ(k.height, kH);
  EXPECT_EQ(k.fx, 30.5);
  EXPECT_EQ(k.fy, 29.25);
  EXPECT_EQ(k.cx, 15.5);
  EXPECT_EQ(k.cy, 11.75);
  EXPECT_NEAR(reader->baseline_m(), 0.04, 1e-9);
  EXPECT_TRUE(reader->HasDepth());
  EXPECT_TRUE(reader->HasSegmentation());
  // trajectory_gt.txt: 9 decimals.
  ExpectGroundTruth(*reader, rec.gt, 5e-9);
  ExpectSameFrames(reader.get(), rec);
}

TEST(ViquDatasetReader, DatasetFolderComposesBodyGroundTruthWithTheCameraExtrinsics) {
  TempDir tmp;
  const ViquRecording rec = RecordViqu(tmp.path() / "run", 3);
  ViquDatasetReader reader((tmp.path() / "run" / "dataset").string());
  // No trajectory_gt.txt next to mav0: state_groundtruth_estimate0 (9 decimals) * T_BS (12 digits).
  ExpectGroundTruth(reader, rec.gt, 1e-7);
  ExpectSameFrames(&reader, rec);
}

TEST(ViquDatasetReader, RejectsARecordingThatIsNotRectified) {
  TempDir tmp;
  sim::EurocRig rig;
  rig.camera.width = kW;
  rig.camera.height = kH;
  rig.camera.depth = rig.camera.segmentation = false;
  rig.intrinsics = {kW, kH, 30, 30, 16, 12};
  rig.T_body_cam0 = CameraInBody();
  rig.T_body_cam1 = rig.T_body_cam0 * Pose(0.01, 0, 0, Eigen::Vector3d(0.04, 0, 0));
  {
    sim::EurocRecorder recorder((tmp.path() / "dataset").string(), rig);
    StereoFrame f;
    f.left_rgb = RandomRgb(kW, kH, 1);
    f.right_rgb = RandomRgb(kW, kH, 2);
    recorder.AddFrame(f);
    recorder.Finish();
  }
  ExpectInputError([&] { ViquDatasetReader r((tmp.path() / "dataset").string()); },
                   {"cam1/sensor.yaml", "not a rectified pair", "--format euroc"});
  // Without depth0/seg0 and ground truth rows the reader says so.
  sim::EurocRig ok = rig;
  ok.T_body_cam1 = rig.T_body_cam0 * Eigen::Translation3d(0.04, 0, 0);
  {
    sim::EurocRecorder recorder((tmp.path() / "dataset").string(), ok);
    StereoFrame f;
    f.left_rgb = RandomRgb(kW, kH, 1);
    f.right_rgb = RandomRgb(kW, kH, 2);
    recorder.AddFrame(f);
    recorder.Finish();
  }
  ViquDatasetReader reader((tmp.path() / "dataset").string());
  EXPECT_FALSE(reader.HasDepth());
  EXPECT_FALSE(reader.HasSegmentation());
  EXPECT_FALSE(reader.ground_truth().has_value());  // the file exists but holds no rows
  StereoFrame f;
  ASSERT_TRUE(reader.Next(&f));
  EXPECT_TRUE(f.left_depth_m.empty());
  EXPECT_TRUE(f.left_instance_id.empty());
}

// Depth quantised as the live run quantises it (sim::QuantiseDepth, TUM's 1/5000 m) comes back
// from depth0 bit for bit, so an rgbd replay of a recording sees the live depth.
TEST(ViquDatasetReader, LiveQuantisedDepthReadsBackBitForBit) {
  TempDir tmp;
  sim::EurocRig rig;
  rig.camera.width = kW;
  rig.camera.height = kH;
  rig.camera.segmentation = false;
  rig.intrinsics = {kW, kH, 30, 30, 16, 12};
  rig.T_body_cam0 = CameraInBody();
  rig.T_body_cam1 = rig.T_body_cam0 * Eigen::Translation3d(0.04, 0, 0);
  StereoFrame f;
  f.t_ns = 7;
  f.left_rgb = RandomRgb(kW, kH, 1);
  f.right_rgb = RandomRgb(kW, kH, 2);
  f.left_depth_m = RandomDepth(kW, kH, 3);
  f.left_depth_m.at<float>(1, 1) = 13.5f;  // beyond 65535 / 5000 m: no depth, live as recorded
  sim::QuantiseDepth(&f.left_depth_m, sim::TumRecorder::kDepthScale);
  EXPECT_EQ(f.left_depth_m.at<float>(1, 1), 0.0f);
  {
    sim::EurocRecorder recorder((tmp.path() / "dataset").string(), rig);
    recorder.AddFrame(f);
    recorder.Finish();
  }
  ViquDatasetReader reader((tmp.path() / "dataset").string());
  StereoFrame got;
  ASSERT_TRUE(reader.Next(&got));
  ASSERT_EQ(got.left_depth_m.type(), CV_32F);
  EXPECT_EQ(MaxAbsDiff(got.left_depth_m, f.left_depth_m), 0.0);
}

// A detector model with wrong categories reports one id under several categories: the reader
// gives each frame the list the recorder was given for it (seg0/frame_instances.csv), not one
// category per id.
TEST(ViquDatasetReader, GivesEachFrameItsOwnInstanceList) {
  TempDir tmp;
  sim::EurocRig rig;
  rig.camera.width = kW;
  rig.camera.height = kH;
  rig.intrinsics = {kW, kH, 30, 30, 16, 12};
  rig.T_body_cam0 = CameraInBody();
  rig.T_body_cam1 = rig.T_body_cam0 * Eigen::Translation3d(0.04, 0, 0);
  const Category category_of_5[] = {Category::kPerson, Category::kFurniture, Category::kBox};
  std::vector<StereoFrame> frames;
  {
    sim::EurocRecorder recorder((tmp.path() / "dataset").string(), rig);
    for (int i = 0; i < 4; ++i) {
      StereoFrame f;
      f.t_ns = 1000 + i;
      f.left_rgb = RandomRgb(kW, kH, 1 + i);
      f.right_rgb = RandomRgb(kW, kH, 11 + i);
      f.left_instance_id = cv::Mat(kH, kW, CV_16U, cv::Scalar(0));
      if (i < 3) {
        f.left_instance_id(cv::Rect(1, 1, 4, 4)).setTo(5);
        f.left_instance_id(cv::Rect(10, 1, 4, 4)).setTo(65535);
        // Spurious mask first, then the real one, then the background: not in order of id.
        f.instances = {{65535, Category::kBall, "spurious_" + std::to_string(i + 1)},
                       {5, category_of_5[i], "alice"},
                       {0, Category::kBackground, "background"}};
      }  // frame 3: an empty mask without instances (latency)
      recorder.AddFrame(f);
      frames.push_back(f);
    }
    recorder.Finish();
  }
  const fs::path seg0 = tmp.path() / "dataset" / "mav0" / "seg0";
  {
    ViquDatasetReader reader((tmp.path() / "dataset").string());
    StereoFrame f;
    for (int i = 0; i < 4; ++i) {
      ASSERT_TRUE(reader.Next(&f));
      EXPECT_EQ(MaxAbsDiff(f.left_instance_id, frames[i].left_instance_id), 0.0);
      if (i == 3) {
        EXPECT_TRUE(f.instances.empty());
        continue;
      }
      ASSERT_EQ(f.instances.size(), 3u) << i;
      EXPECT_EQ(f.instances[0].id, 0);
      EXPECT_EQ(f.instances[1].id, 5);
      EXPECT_EQ(f.instances[1].category, category_of_5[i]) << i;
      EXPECT_EQ(f.instances[1].name, "alice");
      EXPECT_EQ(f.instances[2].id, 65535);
      EXPECT_EQ(f.instances[2].category, Category::kBall);
      EXPECT_EQ(f.instances[2].name, "spurious_" + std::to_string(i + 1));
    }
    EXPECT_FALSE(reader.Next(&f));
  }
  // A recording without frame_instances.csv (made before it existed): instances.csv rows of the
  // ids in the image, one category per id (person: first of three equally frequent ones).
  const std::string per_frame = ReadAllText(seg0 / "frame_instances.csv");
  fs::remove(seg0 / "frame_instances.csv");
  {
    ViquDatasetReader reader((tmp.path() / "dataset").string());
    StereoFrame f;
    for (int i = 0; i < 4; ++i) {
      ASSERT_TRUE(reader.Next(&f));
      ASSERT_EQ(f.instances.size(), i < 3 ? 3u : 1u) << i;  // frame 3: the background alone
      if (i == 3) continue;
      EXPECT_EQ(f.instances[1].category, Category::kPerson) << i;
      EXPECT_EQ(f.instances[2].name, "spurious_1") << i;
    }
  }
  // An id in the image that the frame's list lacks: InputError naming the image and the list.
  WriteText(seg0 / "frame_instances.csv", per_frame);
  cv::Mat ids = frames[1].left_instance_id.clone();
  ids.at<uint16_t>(20, 30) = 77;
  ASSERT_TRUE(cv::imwrite((seg0 / "data" / "1001.png").string(), ids));
  {
    ViquDatasetReader reader((tmp.path() / "dataset").string());
    StereoFrame f;
    ASSERT_TRUE(reader.Next(&f));
    ExpectInputError([&] { reader.Next(&f); }, {(seg0 / "data" / "1001.png").string(), "instance id 77", "x=30, y=20",
                                                 "frame_instances.csv"});
  }
  // Malformed lists: FILE:LINE.
  WriteText(seg0 / "frame_instances.csv", "#timestamp [ns],id,category,name\n1000,5,person,alice\n1000,5,box,alice\n");
  ExpectInputError([&] { ViquDatasetReader r((tmp.path() / "dataset").string()); },
                   {"frame_instances.csv:3", "id 5 is listed twice for timestamp 1000"});
  WriteText(seg0 / "frame_instances.csv", "1001,5,person,alice\n1000,5,person,alice\n");
  ExpectInputError([&] { ViquDatasetReader r((tmp.path() / "dataset").string()); },
                   {"frame_instances.csv:2", "timestamp 1000 follows 1001"});
  WriteText(seg0 / "frame_instances.csv", "1000,5,dog,alice\n");
  ExpectInputError([&] { ViquDatasetReader r((tmp.path() / "dataset").string()); },
                   {"frame_instances.csv:1", "unknown category 'dog'"});
  WriteText(seg0 / "frame_instances.csv", "1000,5,person\n");
  ExpectInputError([&] { ViquDatasetReader r((tmp.path() / "dataset").string()); },
                   {"frame_instances.csv:1", "expected 'timestamp [ns],id,category,name'"});
}

// ---------------------------------------------------------------------------------------------
// TUM RGB-D: written by sim::TumRecorder, read by TumDatasetReader

TEST(TumRecorder, WritesOnlyOnFinishAndRemovesThePartialFolderOtherwise) {
  TempDir tmp;
  const PinholeIntrinsics k{kW, kH, 30, 30, 16, 12};
  StereoFrame f;
  f.t_ns = 5;
  f.left_rgb = RandomRgb(kW, kH, 3);
  {
    sim::TumRecorder rec((tmp.path() / "tum").string(), k);
    rec.AddFrame(f);
    EXPECT_TRUE(fs::is_directory(tmp.path() / "tum.partial"));
    EXPECT_FALSE(fs::exists(tmp.path() / "tum"));
    f.t_ns = 4;
    EXPECT_THROW(rec.AddFrame(f), RunError);  // stamps must increase
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "tum.partial"));
  EXPECT_FALSE(fs::exists(tmp.path() / "tum"));
  {
    sim::TumRecorder rec((tmp.path() / "tum").string(), k);
    rec.AddFrame(f);
    rec.Finish();
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "tum.partial"));
  for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt", "camera.yaml", "rgb/0.000000004.png"}) {
    EXPECT_TRUE(fs::is_regular_file(tmp.path() / "tum" / name)) << name;
  }
}

TEST(TumDatasetReader, ReadsATumRecorderDatasetBackExactly) {
  TempDir tmp;
  const PinholeIntrinsics k{kW, kH, 123.456789012345, 121.000000000001, 15.25, 11.125};
  std::vector<StereoFrame> frames;
  std::vector<GroundTruthState> gt;
  {
    sim::TumRecorder rec((tmp.path() / "tum").string(), k);
    for (int i = 0; i < 3; ++i) {
      StereoFrame f;
      f.t_ns = 1305031102123456789LL + i * 33333333LL;
      f.left_rgb = RandomRgb(kW, kH, 30 + i);
      f.right_rgb = RandomRgb(kW, kH, 40 + i);  // not recorded: TUM is RGB-D
      f.left_depth_m = RandomDepth(kW, kH, 50 + i);
      f.left_depth_m.at<float>(0, 0) = 20.0f;   // beyond 65535 / 5000 m: no depth
      rec.AddFrame(f);
      f.left_depth_m.at<float>(0, 0) = 0.0f;
      GroundTruthState g;
      g.t_ns = f.t_ns;
      g.T_w_cam = ToStampedPose(g.t_ns, Pose(0.2 * i, -0.1, 0.3, Eigen::Vector3d(1.0 + i, -2.0, 0.5)));
      rec.AddGroundTruth(g);
      frames.push_back(f);
      gt.push_back(g);
    }
    rec.Finish();
  }
  const std::unique_ptr<DatasetReader> reader = OpenDataset((tmp.path() / "tum").string(), DatasetFormat::kTum);
  EXPECT_EQ(reader->intrinsics().width, kW);
  EXPECT_EQ(reader->intrinsics().height, kH);
  EXPECT_EQ(reader->intrinsics().fx, k.fx);  // camera.yaml holds round-trip digits
  EXPECT_EQ(reader->intrinsics().fy, k.fy);
  EXPECT_EQ(reader->intrinsics().cx, k.cx);
  EXPECT_EQ(reader->intrinsics().cy, k.cy);
  EXPECT_EQ(reader->baseline_m(), 0.0);
  EXPECT_TRUE(reader->HasDepth());
  EXPECT_FALSE(reader->HasSegmentation());
  ExpectGroundTruth(*reader, gt, 5e-9);
  ASSERT_EQ(reader->NumFrames(), 3u);
  StereoFrame f;
  for (const StereoFrame& want : frames) {
    ASSERT_TRUE(reader->Next(&f));
    EXPECT_EQ(f.t_ns, want.t_ns);  // exact from the 9-decimal seconds
    EXPECT_EQ(MaxAbsDiff(f.left_rgb, want.left_rgb), 0.0);
    EXPECT_TRUE(f.right_rgb.empty());
    EXPECT_EQ(f.baseline_m, 0.0);
    ASSERT_EQ(f.left_depth_m.type(), CV_32F);
    cv::Mat diff;
    cv::absdiff(f.left_depth_m, want.left_depth_m, diff);
    EXPECT_LE(cv::norm(diff, cv::NORM_INF), 0.5 / 5000 + 1e-6);  // half a PNG unit
    EXPECT_EQ(cv::countNonZero(f.left_depth_m == 0), cv::countNonZero(want.left_depth_m == 0));
  }
  EXPECT_FALSE(reader->Next(&f));
}

// A TUM sequence as published: comment lines, depth stamps a little off the colour stamps.
void WriteTumSequence(const fs::path& dir, const std::vector<double>& rgb_s, const std::vector<double>& depth_s) {
  std::string rgb = "# color images\n# file: 'test.bag'\n# timestamp filename\n";
  std::string depth = "# depth maps\n# file: 'test.bag'\n# timestamp filename\n";
  char buf[128];
  for (size_t i = 0; i < rgb_s.size(); ++i) {
    std::snprintf(buf, sizeof(buf), "%.6f", rgb_s[i]);
    rgb += std::string(buf) + " rgb/" + buf + ".png\n";
    fs::create_directories(dir / "rgb");
    cv::imwrite((dir / "rgb" / (std::string(buf) + ".png")).string(), RandomRgb(640, 480, 60 + i));
  }
  for (size_t i = 0; i < depth_s.size(); ++i) {
    std::snprintf(buf, sizeof(buf), "%.6f", depth_s[i]);
    depth += std::string(buf) + " depth/" + buf + ".png\n";
    fs::create_directories(dir / "depth");
    cv::imwrite((dir / "depth" / (std::string(buf) + ".png")).string(), cv::Mat(480, 640, CV_16U, cv::Scalar(10000)));
  }
  WriteText(dir / "rgb.txt", rgb);
  WriteText(dir / "depth.txt", depth);
}

TEST(TumDatasetReader, AssociatesLikeAssociatePyAndUsesTheFreiburgCalibration) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "rgbd_dataset_freiburg1_xyz";
  // Colour at 0, 0.033, 0.066, 0.1; depth 10 ms later, except none near 0.066.
  WriteTumSequence(dir, {1305031102.175304, 1305031102.211214, 1305031102.243211, 1305031102.275326},
                   {1305031102.185304, 1305031102.221214, 1305031102.285326});
  testing::internal::CaptureStderr();
  TumDatasetReader reader(dir.string());
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("1 of 4 images have no partner"), std::string::npos) << err;
  EXPECT_FALSE(reader.ground_truth().has_value());
  EXPECT_EQ(reader.NumFrames(), 3u);
  EXPECT_EQ(reader.intrinsics().fx, 517.3);
  EXPECT_EQ(reader.intrinsics().cy, 255.3);
  EXPECT_NE(reader.camera_source().find("freiburg1"), std::string::npos);
  StereoFrame f;
  std::vector<int64_t> stamps;
  while (reader.Next(&f)) {
    stamps.push_back(f.t_ns);
    // freiburg1 is distorted: undistorted on reading; the centre keeps its depth (10000 / 5000).
    EXPECT_FLOAT_EQ(f.left_depth_m.at<float>(240, 320), 2.0f);
  }
  EXPECT_EQ(stamps, (std::vector<int64_t>{1305031102175304000LL, 1305031102211214000LL, 1305031102275326000LL}));

  // freiburg3 by its folder name.
  const fs::path fr3_dir = tmp.path() / "rgbd_dataset_freiburg3_office";
  WriteTumSequence(fr3_dir, {1.0}, {1.001});
  WriteText(fr3_dir / "groundtruth.txt", "# ground truth\n0.99 1 2 3 0 0 0 1\n1.01 1 2 3 0 0 0 1\n");
  TumDatasetReader fr3(fr3_dir.string());
  EXPECT_EQ(fr3.intrinsics().fx, 535.4);
  EXPECT_EQ(fr3.intrinsics().fy, 539.2);
  EXPECT_EQ(fr3.intrinsics().cx, 320.1);
  EXPECT_EQ(fr3.intrinsics().cy, 247.6);
  ASSERT_TRUE(fr3.ground_truth().has_value());
  EXPECT_EQ(fr3.ground_truth()->size(), 2u);

  // No calibration and no freiburgN in the name: no guess, the message names --camera.
  const fs::path plain = tmp.path() / "some_sequence";
  WriteTumSequence(plain, {1.0}, {1.001});
  ExpectInputError([&] { TumDatasetReader r(plain.string()); }, {"some_sequence: no camera calibration", "--camera FILE"});
  WriteText(plain / "camera.yaml", "fx: 500\nfy: 501\ncx: 320\ncy: 240\nwidth: 640\nheight: 480\n");
  EXPECT_EQ(TumDatasetReader(plain.string()).intrinsics().fy, 501.0);
  WriteText(plain / "viqu_intrinsics.yaml", "fx: 400\nfy: 401\ncx: 320\ncy: 240\nwidth: 640\nheight: 480\n");
  EXPECT_EQ(TumDatasetReader(plain.string()).intrinsics().fy, 401.0);  // preferred over camera.yaml
  WriteText(plain / "viqu_intrinsics.yaml", "fx: 400\nfy: 401\ncx: 320\ncy: 240\nwidth: 640\nheight: 480\nfocal: 3\n");
  ExpectInputError([&] { TumDatasetReader r(plain.string()); }, {"viqu_intrinsics.yaml:7:1", "unknown key 'focal'"});
  WriteText(plain / "viqu_intrinsics.yaml", "fx: 400\nfy: 401\ncx: 320\ncy: 240\nwidth: 320\nheight: 240\n");
  // A calibration of another image size is named when the folder is opened.
  ExpectInputError([&] { TumDatasetReader r(plain.string()); },
                   {"viqu_intrinsics.yaml: the calibration is for 320x240 images", ".png is 640x480"});
}

// ---------------------------------------------------------------------------------------------
// EuRoC MAV: a synthetic distorted pair with a small rotation between the cameras

struct RawCamera {
  PinholeIntrinsics k;
  std::vector<double> d;      // k1, k2, p1, p2
  Eigen::Isometry3d T_B_C;    // camera in body
};

struct SyntheticEuroc {
  RawCamera cam0, cam1;
  Eigen::Isometry3d T_B_imu;
  std::vector<int64_t> stamps;                    // frame stamps (ns)
  std::vector<Eigen::Isometry3d> T_w_imu;         // at the frame stamps
  std::vector<Eigen::Vector3d> points_cam0;       // blob centres in the raw cam0 frame (m)
};

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

// The 16 values of a 4x4 transform, row-major, comma-separated.
std::string MatrixData(const Eigen::Isometry3d& T) {
  std::string d;
  const Eigen::Matrix4d m = T.matrix();
  for (int i = 0; i < 16; ++i) d += Num(m(i / 4, i % 4)) + (i < 15 ? ", " : "");
  return d;
}

std::string SensorYaml(const RawCamera& c) {
  std::string s = "%YAML:1.0\n---\n# General sensor definitions.\nsensor_type: camera\ncomment: synthetic\n\n"
                  "# Sensor extrinsics wrt. the body-frame.\nT_BS:\n  cols: 4\n  rows: 4\n  data: [";
  s += MatrixData(c.T_B_C) + "]\n";
  const PinholeIntrinsics& k = c.k;
  s += "\n# Camera specific definitions.\nrate_hz: 20\n";
  s += "resolution: [" + std::to_string(k.width) + ", " + std::to_string(k.height) + "]\ncamera_model: pinhole\n";
  s += "intrinsics: [" + Num(k.fx) + ", " + Num(k.fy) + ", " + Num(k.cx) + ", " + Num(k.cy) + "] #fu, fv, cu, cv\n";
  s += "distortion_model: radial-tangential\n";
  s += "distortion_coefficients: [" + Num(c.d[0]) + ", " + Num(c.d[1]) + ", " + Num(c.d[2]) + ", " + Num(c.d[3]);
  s += "]\n";
  return s;
}

// Pixel positions of points (camera frame, m) in the raw (distorted) image of camera `c`.
std::vector<cv::Point2d> DistortedProjections(const RawCamera& c, const std::vector<Eigen::Vector3d>& points_c) {
  std::vector<cv::Point3d> obj;
  for (const Eigen::Vector3d& p : points_c) obj.emplace_back(p.x(), p.y(), p.z());
  const cv::Matx33d K(c.k.fx, 0, c.k.cx, 0, c.k.fy, c.k.cy, 0, 0, 1);
  std::vector<cv::Point2d> px;
  cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, c.d, px);
  return px;
}

// Grey image with a Gaussian blob (sigma 1.5 px) at the distorted projection of every point.
cv::Mat RenderBlobs(const RawCamera& c, const std::vector<Eigen::Vector3d>& points_c) {
  const std::vector<cv::Point2d> px = DistortedProjections(c, points_c);
  cv::Mat img(c.k.height, c.k.width, CV_32F, cv::Scalar(0));
  const double sigma = 1.5;
  for (const cv::Point2d& q : px) {
    for (int v = static_cast<int>(q.y) - 7; v <= static_cast<int>(q.y) + 7; ++v) {
      for (int u = static_cast<int>(q.x) - 7; u <= static_cast<int>(q.x) + 7; ++u) {
        if (u < 0 || v < 0 || u >= img.cols || v >= img.rows) continue;
        const double r2 = (u - q.x) * (u - q.x) + (v - q.y) * (v - q.y);
        img.at<float>(v, u) += static_cast<float>(250.0 * std::exp(-r2 / (2 * sigma * sigma)));
      }
    }
  }
  cv::Mat grey;
  img.convertTo(grey, CV_8U);
  return grey;
}

// Intensity-weighted centroids of the bright blobs of an RGB image.
std::vector<cv::Point2d> BlobCentroids(const cv::Mat& rgb) {
  cv::Mat grey;
  cv::extractChannel(rgb, grey, 0);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(grey > 20, labels, stats, centroids);
  std::vector<cv::Point2d> out;
  for (int l = 1; l < n; ++l) {
    double sw = 0, su = 0, sv = 0;
    for (int v = 0; v < grey.rows; ++v) {
      for (int u = 0; u < grey.cols; ++u) {
        if (labels.at<int>(v, u) != l) continue;
        const double w = grey.at<uint8_t>(v, u);
        sw += w;
        su += w * u;
        sv += w * v;
      }
    }
    out.emplace_back(su / sw, sv / sw);
  }
  return out;
}

cv::Point2d Nearest(const std::vector<cv::Point2d>& pts, const cv::Point2d& q) {
  cv::Point2d best(1e9, 1e9);
  for (const cv::Point2d& p : pts) {
    if (cv::norm(p - q) < cv::norm(best - q)) best = p;
  }
  return best;
}

SyntheticEuroc MakeEurocRig() {
  SyntheticEuroc s;
  s.cam0.k = {320, 240, 300.0, 302.0, 161.3, 119.2};
  s.cam0.d = {-0.05, 0.01, 0.0005, -0.0003};
  s.cam0.T_B_C = Pose(-M_PI / 2, 0.02, -M_PI / 2, Eigen::Vector3d(0.05, -0.02, 0.01));
  s.cam1.k = {320, 240, 298.0, 299.0, 158.7, 121.5};
  s.cam1.d = {-0.04, 0.008, -0.0004, 0.0002};
  Eigen::Isometry3d T_cam0_cam1 = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, 1.0, 0.3).normalized();
  T_cam0_cam1.linear() = Eigen::AngleAxisd(0.8 * M_PI / 180, axis).toRotationMatrix();  // 0.8 deg
  T_cam0_cam1.translation() = Eigen::Vector3d(0.11, 0.003, -0.002);
  s.cam1.T_B_C = s.cam0.T_B_C * T_cam0_cam1;
  s.T_B_imu = Pose(0.01, -0.02, 0.015, Eigen::Vector3d(0.01, 0.02, 0.03));
  for (int gy = -1; gy <= 1; ++gy) {
    for (int gx = -1; gx <= 1; ++gx) {
      const double z = 2.0 + 0.5 * (3 * (gy + 1) + gx + 1);
      s.points_cam0.emplace_back(0.25 * gx * z + 0.01, 0.2 * gy * z - 0.02, z);
    }
  }
  return s;
}

// Writes mav0/ of a EuRoC dataset with `n` stereo frames of blobs; returns the dataset folder.
SyntheticEuroc WriteEuroc(const fs::path& dir, int n) {
  SyntheticEuroc s = MakeEurocRig();
  const fs::path mav0 = dir / "mav0";
  WriteText(mav0 / "cam0" / "sensor.yaml", SensorYaml(s.cam0));
  WriteText(mav0 / "cam1" / "sensor.yaml", SensorYaml(s.cam1));
  WriteText(mav0 / "imu0" / "sensor.yaml", "%YAML:1.0\n---\nsensor_type: imu\nT_BS:\n  cols: 4\n  rows: 4\n  data: [" +
                                                MatrixData(s.T_B_imu) + "]\nrate_hz: 200\n");
  std::string csv0 = "#timestamp [ns],filename\r\n", csv1 = "#timestamp [ns],filename\n";
  std::string gt = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z []\n";
  fs::create_directories(mav0 / "cam0" / "data");
  fs::create_directories(mav0 / "cam1" / "data");
  const Eigen::Isometry3d T_cam0_cam1 = s.cam0.T_B_C.inverse() * s.cam1.T_B_C;
  for (int i = 0; i < n; ++i) {
    const int64_t t = 1403636579763555584LL + i * 50000000LL;
    s.stamps.push_back(t);
    s.T_w_imu.push_back(Pose(0.4 * i, 0.1, -0.05, Eigen::Vector3d(4.6 + 0.1 * i, -1.7, 0.8)));
    const std::string name = std::to_string(t) + ".png";
    // The blobs move with the frame so that a mix-up of frames would show.
    std::vector<Eigen::Vector3d> p0 = s.points_cam0, p1;
    for (Eigen::Vector3d& p : p0) p.x() += 0.02 * i;
    for (const Eigen::Vector3d& p : p0) p1.push_back(T_cam0_cam1.inverse() * p);
    cv::imwrite((mav0 / "cam0" / "data" / name).string(), RenderBlobs(s.cam0, p0));
    cv::imwrite((mav0 / "cam1" / "data" / name).string(), RenderBlobs(s.cam1, p1));
    csv0 += std::to_string(t) + "," + name + "\r\n";  // EuRoC files come with CRLF line ends
    csv1 += std::to_string(t) + "," + name + "\n";
    // Ground truth at twice the camera rate.
    for (int h = 0; h < 2; ++h) {
      const Eigen::Isometry3d T =
          h == 0 ? s.T_w_imu.back() : s.T_w_imu.back() * Pose(0.01, 0, 0, Eigen::Vector3d(0.001, 0, 0));
      const Eigen::Quaterniond q(T.linear());
      gt += std::to_string(t + h * 25000000LL) + "," + Num(T.translation().x()) + "," + Num(T.translation().y()) + "," +
            Num(T.translation().z()) + "," + Num(q.w()) + "," + Num(q.x()) + "," + Num(q.y()) + "," + Num(q.z()) +
            ",0,0,0,0,0,0,0,0,0\n";
    }
  }
  WriteText(mav0 / "cam0" / "data.csv", csv0);
  WriteText(mav0 / "cam1" / "data.csv", csv1);
  WriteText(mav0 / "state_groundtruth_estimate0" / "data.csv", gt);
  return s;
}

TEST(EurocDatasetReader, RectifiesToRowAlignedImagesWithTheTrueBaselineAndCameraPose) {
  TempDir tmp;
  const SyntheticEuroc s = WriteEuroc(tmp.path() / "MH_synthetic", 2);
  const std::unique_ptr<DatasetReader> reader =
      OpenDataset((tmp.path() / "MH_synthetic").string(), DatasetFormat::kEuroc);
  const Eigen::Isometry3d T_cam0_cam1 = s.cam0.T_B_C.inverse() * s.cam1.T_B_C;
  EXPECT_NEAR(reader->baseline_m(), T_cam0_cam1.translation().norm(), 1e-9);
  EXPECT_FALSE(reader->HasDepth());
  const PinholeIntrinsics& k = reader->intrinsics();
  EXPECT_EQ(k.width, 320);
  EXPECT_EQ(k.height, 240);
  ASSERT_EQ(reader->NumFrames(), 2u);
  ASSERT_TRUE(reader->ground_truth().has_value());
  const std::vector<StampedPose>& gt = *reader->ground_truth();
  ASSERT_EQ(gt.size(), 4u);

  StereoFrame f;
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(reader->Next(&f));
    EXPECT_EQ(f.t_ns, s.stamps[i]);
    ASSERT_EQ(f.left_rgb.type(), CV_8UC3);
    ASSERT_EQ(f.right_rgb.type(), CV_8UC3);
    EXPECT_EQ(f.baseline_m, reader->baseline_m());
    // Ground truth row 2i is at the frame stamp: T_w_rect0 = T_w_imu * T_B_imu^-1 * T_B_cam0 * R1^T.
    ASSERT_EQ(gt[2 * i].t_ns, f.t_ns);
    const Eigen::Isometry3d T_w_cam0 = s.T_w_imu[i] * s.T_B_imu.inverse() * s.cam0.T_B_C;
    EXPECT_LT((gt[2 * i].p_w_x - T_w_cam0.translation()).norm(), 1e-9);  // rectification only rotates
    const Eigen::Isometry3d T_w_rect0 = ToIsometry(gt[2 * i]);

    const std::vector<cv::Point2d> left = BlobCentroids(f.left_rgb), right = BlobCentroids(f.right_rgb);
    EXPECT_EQ(left.size(), s.points_cam0.size());
    EXPECT_EQ(right.size(), s.points_cam0.size());
    for (Eigen::Vector3d p_cam0 : s.points_cam0) {
      p_cam0.x() += 0.02 * i;
      // The point through the reader's ground-truth pose and rectified intrinsics.
      const Eigen::Vector3d p = T_w_rect0.inverse() * (T_w_cam0 * p_cam0);
      const cv::Point2d want_l(k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy);
      const cv::Point2d want_r(want_l.x - k.fx * reader->baseline_m() / p.z(), want_l.y);
      const cv::Point2d got_l = Nearest(left, want_l), got_r = Nearest(right, want_r);
      EXPECT_LT(cv::norm(got_l - want_l), 0.25) << "left " << got_l << " want " << want_l;
      EXPECT_LT(cv::norm(got_r - want_r), 0.25) << "right " << got_r << " want " << want_r;
      EXPECT_LT(std::abs(got_l.y - got_r.y), 0.5) << got_l << " " << got_r;
    }
  }
  EXPECT_FALSE(reader->Next(&f));
}

// ---------------------------------------------------------------------------------------------
// Instance masks of an external detector (--masks, docs/MASKS.md) through the three readers

void WriteMask(const fs::path& path, const cv::Mat& ids) {
  fs::create_directories(path.parent_path());
  ASSERT_TRUE(cv::imwrite(path.string(), ids)) << path;
}

// The distinct values of a CV_16U image.
std::set<uint16_t> IdsIn(const cv::Mat& ids) {
  std::set<uint16_t> out;
  for (int v = 0; v < ids.rows; ++v) {
    for (int u = 0; u < ids.cols; ++u) out.insert(ids.at<uint16_t>(v, u));
  }
  return out;
}

// Mean pixel position of the pixels holding `id`.
cv::Point2d CentroidOf(const cv::Mat& ids, uint16_t id) {
  double su = 0, sv = 0, n = 0;
  for (int v = 0; v < ids.rows; ++v) {
    for (int u = 0; u < ids.cols; ++u) {
      if (ids.at<uint16_t>(v, u) != id) continue;
      su += u;
      sv += v;
      n += 1;
    }
  }
  return {su / n, sv / n};
}

TEST(DatasetMasks, EurocMasksGoThroughTheLeftRectificationByNearestNeighbour) {
  TempDir tmp;
  const SyntheticEuroc s = WriteEuroc(tmp.path() / "MH_synthetic", 2);
  // A disc of radius 6 px around every blob of frame 0 in the raw cam0 image, each its own id;
  // frame 1 has no mask file.
  const fs::path masks = tmp.path() / "masks";
  std::string csv = "#id,category,name\n";
  std::vector<uint16_t> ids;
  cv::Mat raw_ids(s.cam0.k.height, s.cam0.k.width, CV_16U, cv::Scalar(0));
  const std::vector<cv::Point2d> centres = DistortedProjections(s.cam0, s.points_cam0);
  for (size_t k = 0; k < centres.size(); ++k) {
    ids.push_back(static_cast<uint16_t>(5000 * (k + 1)));
    csv += std::to_string(ids[k]) + "," + (k % 2 ? "box" : "person") + ",object_" + std::to_string(k) + "\n";
    for (int v = 0; v < raw_ids.rows; ++v) {
      for (int u = 0; u < raw_ids.cols; ++u) {
        if (std::hypot(u - centres[k].x, v - centres[k].y) <= 6.0) raw_ids.at<uint16_t>(v, u) = ids[k];
      }
    }
  }
  csv += "50001,ball,never_in_view\n";
  WriteText(masks / "instances.csv", csv);
  WriteMask(masks / (std::to_string(s.stamps[0]) + ".png"), raw_ids);

  const std::unique_ptr<DatasetReader> reader =
      OpenDataset((tmp.path() / "MH_synthetic").string(), DatasetFormat::kEuroc, masks.string());
  EXPECT_TRUE(reader->HasSegmentation());
  const PinholeIntrinsics& k = reader->intrinsics();
  StereoFrame f;
  ASSERT_TRUE(reader->Next(&f));
  ASSERT_EQ(f.left_instance_id.type(), CV_16U);
  ASSERT_EQ(f.left_instance_id.size(), f.left_rgb.size());
  // Nearest neighbour: every value is one of the input's (linear interpolation between 5000
  // and 0 or 10000 would give others), and every disc survives.
  std::set<uint16_t> want_ids(ids.begin(), ids.end());
  want_ids.insert(0);
  EXPECT_EQ(IdsIn(f.left_instance_id), want_ids);
  // Each disc lands where its blob lands in the rectified left image, within pixel sampling
  // (a third of a pixel here; the fixed-point maps of the images are off by up to 0.46 px).
  const Eigen::Isometry3d T_w_cam0 = s.T_w_imu[0] * s.T_B_imu.inverse() * s.cam0.T_B_C;
  const Eigen::Isometry3d T_w_rect0 = ToIsometry((*reader->ground_truth())[0]);
  for (size_t i = 0; i < ids.size(); ++i) {
    const Eigen::Vector3d p = T_w_rect0.inverse() * (T_w_cam0 * s.points_cam0[i]);
    const cv::Point2d want(k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy);
    const cv::Point2d got = CentroidOf(f.left_instance_id, ids[i]);
    EXPECT_LT(cv::norm(got - want), 0.35) << "id " << ids[i] << ": " << got << " want " << want;
  }
  // instances: the rows of instances.csv whose ids are in view, in order of id.
  ASSERT_EQ(f.instances.size(), ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(f.instances[i].id, ids[i]);
    EXPECT_EQ(f.instances[i].category, i % 2 ? Category::kBox : Category::kPerson);
    EXPECT_EQ(f.instances[i].name, "object_" + std::to_string(i));
  }
  // No mask file: no detections.
  ASSERT_TRUE(reader->Next(&f));
  ASSERT_EQ(f.left_instance_id.type(), CV_16U);
  ASSERT_EQ(f.left_instance_id.size(), f.left_rgb.size());
  EXPECT_EQ(cv::countNonZero(f.left_instance_id), 0);
  EXPECT_TRUE(f.instances.empty());
  // Without --masks nothing changes.
  EurocDatasetReader plain((tmp.path() / "MH_synthetic").string());
  EXPECT_FALSE(plain.HasSegmentation());
  ASSERT_TRUE(plain.Next(&f));
  EXPECT_TRUE(f.left_instance_id.empty());
  EXPECT_TRUE(f.instances.empty());
}

TEST(DatasetMasks, TumMasksAreNamedLikeTheRgbImagesAndUndistortedWithThem) {
  TempDir tmp;
  const fs::path masks = tmp.path() / "masks";
  WriteText(masks / "instances.csv", "#id,category,name\n5,person,alice\n9,furniture,chair\n");
  // freiburg3 (no distortion): the mask comes back exactly.
  const fs::path fr3 = tmp.path() / "rgbd_dataset_freiburg3_masks";
  WriteTumSequence(fr3, {1.0, 1.1}, {1.001, 1.101});
  cv::Mat ids(480, 640, CV_16U, cv::Scalar(0));
  ids(cv::Rect(100, 50, 80, 200)).setTo(9);
  WriteMask(masks / "1.000000.png", ids);
  TumDatasetReader reader(fr3.string(), masks.string());
  EXPECT_TRUE(reader.HasSegmentation());
  StereoFrame f;
  ASSERT_TRUE(reader.Next(&f));
  EXPECT_EQ(MaxAbsDiff(f.left_instance_id, ids), 0.0);
  ASSERT_EQ(f.instances.size(), 1u);
  EXPECT_EQ(f.instances[0].id, 9);
  EXPECT_EQ(f.instances[0].category, Category::kFurniture);
  EXPECT_EQ(f.instances[0].name, "chair");
  ASSERT_TRUE(reader.Next(&f));  // rgb/1.100000.png has no mask
  EXPECT_EQ(f.left_instance_id.size(), cv::Size(640, 480));
  EXPECT_EQ(cv::countNonZero(f.left_instance_id), 0);
  EXPECT_TRUE(f.instances.empty());

  // freiburg1 (distorted): the mask is undistorted with the image, never blending 5 and 9.
  const fs::path fr1 = tmp.path() / "rgbd_dataset_freiburg1_xyz";
  WriteTumSequence(fr1, {1.0}, {1.001});
  ids.setTo(5);
  ids.colRange(320, 640).setTo(9);
  WriteMask(masks / "1.000000.png", ids);
  TumDatasetReader distorted(fr1.string(), masks.string());
  ASSERT_TRUE(distorted.Next(&f));
  const std::set<uint16_t> seen = IdsIn(f.left_instance_id);
  EXPECT_TRUE(seen.count(5) && seen.count(9));
  for (uint16_t id : seen) EXPECT_TRUE(id == 0 || id == 5 || id == 9) << id;
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(240, 300), 5);
  EXPECT_EQ(f.left_instance_id.at<uint16_t>(240, 340), 9);

  // An id that instances.csv does not list: InputError naming the mask.
  ids.at<uint16_t>(10, 10) = 6;
  WriteMask(masks / "1.000000.png", ids);
  TumDatasetReader unknown(fr1.string(), masks.string());
  ExpectInputError([&] { unknown.Next(&f); }, {(masks / "1.000000.png").string(), "instance id 6"});
}

TEST(DatasetMasks, MasksReplaceTheSeg0OfAViquRecording) {
  TempDir tmp;
  const ViquRecording rec = RecordViqu(tmp.path() / "run", 3);
  const fs::path masks = tmp.path() / "masks";
  WriteText(masks / "instances.csv", "id,category,name\n42,ball,red_ball\n");
  cv::Mat ids(kH, kW, CV_16U, cv::Scalar(0));
  ids(cv::Rect(10, 5, 4, 4)).setTo(42);
  const auto mask_of = [&](int i) { return masks / (std::to_string(rec.frames[i].t_ns) + ".png"); };
  WriteMask(mask_of(0), ids);
  const std::unique_ptr<DatasetReader> reader =
      OpenDataset((tmp.path() / "run").string(), DatasetFormat::kViqu, masks.string());
  EXPECT_TRUE(reader->HasSegmentation());
  StereoFrame f;
  ASSERT_TRUE(reader->Next(&f));
  EXPECT_EQ(MaxAbsDiff(f.left_instance_id, ids), 0.0);
  ASSERT_EQ(f.instances.size(), 1u);
  EXPECT_EQ(f.instances[0].id, 42);
  EXPECT_EQ(f.instances[0].name, "red_ball");
  // Frame 1 has seg0 (a person and a box) but no mask: no detections.
  ASSERT_TRUE(reader->Next(&f));
  EXPECT_EQ(cv::countNonZero(f.left_instance_id), 0);
  EXPECT_TRUE(f.instances.empty());
  // A mask of the wrong size: InputError naming it.
  WriteMask(mask_of(2), cv::Mat(kH + 1, kW, CV_16U, cv::Scalar(0)));
  ExpectInputError([&] { reader->Next(&f); }, {mask_of(2).string(), "mask is 32x25", "image is 32x24"});
  // A masks folder without instances.csv is refused when the dataset is opened.
  fs::remove(masks / "instances.csv");
  ExpectInputError([&] { OpenDataset((tmp.path() / "run").string(), DatasetFormat::kViqu, masks.string()); },
                   {(masks / "instances.csv").string(), "not found"});
}

// ---------------------------------------------------------------------------------------------
// Bad input

TEST(DatasetIoBadInput, MissingFolderOrUnknownFormat) {
  TempDir tmp;
  const std::string missing = (tmp.path() / "nothing_here").string();
  for (DatasetFormat format : {DatasetFormat::kViqu, DatasetFormat::kEuroc, DatasetFormat::kTum}) {
    ExpectInputError([&] { OpenDataset(missing, format); }, {missing, "not found"});
  }
  ExpectInputError([&] { ParseDatasetFormat("kitti"); }, {"kitti", "viqu, euroc, tum"});
  EXPECT_EQ(ParseDatasetFormat("euroc"), DatasetFormat::kEuroc);
  // A folder that exists but is no dataset.
  ExpectInputError([&] { OpenDataset(tmp.path().string(), DatasetFormat::kEuroc); }, {"no mav0/"});
  ExpectInputError([&] { OpenDataset(tmp.path().string(), DatasetFormat::kViqu); }, {"not a viqu recording"});
  const fs::path tum_as_viqu = tmp.path() / "tum_sequence";
  WriteTumSequence(tum_as_viqu, {1.0}, {1.0});
  ExpectInputError([&] { OpenDataset(tum_as_viqu.string(), DatasetFormat::kViqu); }, {"not a viqu recording", "--format tum"});
  ExpectInputError([&] { OpenDataset(tmp.path().string(), DatasetFormat::kTum); }, {"rgb.txt", "not found"});
}

TEST(DatasetIoBadInput, EmptyMalformedOrBackwardsListsNameFileAndLine) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "euroc";
  WriteEuroc(dir, 3);
  const fs::path csv = dir / "mav0" / "cam0" / "data.csv";
  const std::string header = "#timestamp [ns],filename\n";
  WriteText(csv, header);
  ExpectInputError([&] { EurocDatasetReader r(dir.string()); }, {"cam0/data.csv", "no images"});

  WriteText(csv, header + "1403636579763555584,1403636579763555584.png\n1403636579813555584,a.png,extra\n");
  ExpectInputError([&] { EurocDatasetReader r(dir.string()); }, {"cam0/data.csv:3:", "expected"});
  WriteText(csv, header + "1403636579763555584,1403636579763555584.png\n14036365798x3555584,a.png\n");
  ExpectInputError([&] { EurocDatasetReader r(dir.string()); }, {"cam0/data.csv:3:", "not an integer"});
  WriteText(csv, header + "1403636579763555584,1403636579763555584.png\n\n1403636579713555584,a.png\n");
  ExpectInputError([&] { EurocDatasetReader r(dir.string()); }, {"cam0/data.csv:4:", "backwards"});

  // Ground truth and sensor.yaml errors name their file.
  WriteEuroc(dir, 3);
  WriteText(dir / "mav0" / "state_groundtruth_estimate0" / "data.csv", "#t\n1,0,0,0,1,0,0,0\n2,0,0,0,1,0,nan,0\n");
  ExpectInputError([&] { EurocDatasetReader r(dir.string()); },
                   {"state_groundtruth_estimate0/data.csv:3:", "not a finite number"});
  WriteEuroc(dir, 3);
  WriteText(dir / "mav0" / "cam1" / "sensor.yaml", "%YAML:1.0\n---\nT_BS:\n  data: [1, 0, 0]\n");
  ExpectInputError([&] { EurocDatasetReader r(dir.string()); }, {"cam1/sensor.yaml:4:", "T_BS.data"});

  // TUM list.
  const fs::path tum = tmp.path() / "rgbd_dataset_freiburg3_list";
  WriteTumSequence(tum, {1.0, 1.1}, {1.0, 1.1});
  WriteText(tum / "rgb.txt", "# color\n1.0 rgb/1.000000.png\n1.1\n");
  ExpectInputError([&] { TumDatasetReader r(tum.string()); }, {"rgb.txt:3:", "expected 'timestamp filename'"});
  WriteText(tum / "rgb.txt", "# color\n1.1 rgb/1.100000.png\n1.0 rgb/1.000000.png\n");
  ExpectInputError([&] { TumDatasetReader r(tum.string()); }, {"rgb.txt:3:", "backwards"});
  WriteText(tum / "rgb.txt", "# color\n");
  ExpectInputError([&] { TumDatasetReader r(tum.string()); }, {"rgb.txt", "no images"});
}

TEST(DatasetIoBadInput, ACorruptImageIsAnErrorOrWhenAllowedSkippedAloneButNotTwoInARowOrFirst) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "euroc";
  SyntheticEuroc s = WriteEuroc(dir, 5);
  auto image = [&](int i, const char* cam) {
    return dir / "mav0" / cam / "data" / (std::to_string(s.stamps[i]) + ".png");
  };
  WriteText(image(2, "cam0"), "\x89PNG\r\n\x1a\n truncated");
  {
    // By default an unreadable image is bad input, named.
    EurocDatasetReader reader(dir.string());
    StereoFrame f;
    ASSERT_TRUE(reader.Next(&f));
    ASSERT_TRUE(reader.Next(&f));
    ExpectInputError([&] { reader.Next(&f); }, {image(2, "cam0").string(), "--skip-bad-frames"});
  }
  {
    EurocDatasetReader reader(dir.string());
    reader.AllowSkippingBadFrames(1);
    EXPECT_EQ(reader.NumFrames(), 5u);
    std::vector<int64_t> got;
    StereoFrame f;
    testing::internal::CaptureStderr();
    while (reader.Next(&f)) got.push_back(f.t_ns);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(got, (std::vector<int64_t>{s.stamps[0], s.stamps[1], s.stamps[3], s.stamps[4]}));
    EXPECT_NE(err.find(image(2, "cam0").string()), std::string::npos) << err;
    EXPECT_NE(err.find("frame skipped"), std::string::npos) << err;
    EXPECT_EQ(reader.frames_skipped(), 1);
  }
  fs::remove(image(3, "cam1"));  // a missing file counts as unreadable too
  {
    EurocDatasetReader reader(dir.string());
    reader.AllowSkippingBadFrames(1);
    StereoFrame f;
    ASSERT_TRUE(reader.Next(&f));
    ASSERT_TRUE(reader.Next(&f));
    testing::internal::CaptureStderr();
    ExpectInputError([&] { reader.Next(&f); }, {image(3, "cam1").string(), "second unreadable frame in a row"});
    testing::internal::GetCapturedStderr();
  }
  WriteText(image(0, "cam0"), "");
  {
    EurocDatasetReader reader(dir.string());
    reader.AllowSkippingBadFrames(1);
    StereoFrame f;
    ExpectInputError([&] { reader.Next(&f); }, {image(0, "cam0").string(), "first frame"});
  }
  // The viqu reader follows the same policy, also for depth images.
  const ViquRecording rec = RecordViqu(tmp.path() / "run", 4);
  const fs::path depth = tmp.path() / "run" / "dataset" / "mav0" / "depth0" / "data" /
                         (std::to_string(rec.frames[1].t_ns) + ".png");
  WriteText(depth, "not a png");
  {
    ViquDatasetReader strict((tmp.path() / "run").string());
    StereoFrame f;
    ASSERT_TRUE(strict.Next(&f));
    ExpectInputError([&] { strict.Next(&f); }, {depth.string()});
  }
  ViquDatasetReader reader((tmp.path() / "run").string());
  reader.AllowSkippingBadFrames(1);
  StereoFrame f;
  std::vector<int64_t> got;
  testing::internal::CaptureStderr();
  while (reader.Next(&f)) got.push_back(f.t_ns);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(got, (std::vector<int64_t>{rec.frames[0].t_ns, rec.frames[2].t_ns, rec.frames[3].t_ns}));
}

TEST(CameraFile, RealCalibrationsPassTheSanityCheck) {
  // EuRoC MH_01's cam0 (its sensor.yaml) and TUM's freiburg1 colour camera (published values).
  CameraCalibration euroc;
  euroc.pinhole = {752, 480, 458.654, 457.296, 367.215, 248.375};
  euroc.distortion = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05};
  EXPECT_EQ(CalibrationProblem(euroc, {}, "euroc"), "");
  CameraCalibration fr1;
  fr1.pinhole = {640, 480, 517.306408, 516.469215, 318.643040, 255.313989};
  fr1.distortion = {0.262383, -0.953104, -0.005358, 0.002628, 1.163314};
  EXPECT_EQ(CalibrationProblem(fr1, {}, "fr1"), "");
  // Every key out of range is named, with the source when no key is known.
  CameraCalibration c = fr1;
  c.pinhole.cx = 99999;
  EXPECT_NE(CalibrationProblem(c, {}, "fr1").find("fr1: cx 99999 px is outside the 640x480 image"), std::string::npos);
  c = fr1;
  c.pinhole.fy = 1e300;
  EXPECT_NE(CalibrationProblem(c, {"", "cam.yaml:3:5: key 'fy'", "", "", ""}, "x").find("cam.yaml:3:5: key 'fy': fy 1e+300"),
            std::string::npos);
  c = fr1;
  c.pinhole.fx = 0.5;  // a field of view over 179 deg
  EXPECT_NE(CalibrationProblem(c, {}, "x").find("no focal length"), std::string::npos);
  c = fr1;
  c.distortion = {1e6, 0, 0, 0};
  EXPECT_NE(CalibrationProblem(c, {}, "x").find("scales radii by"), std::string::npos);
  c = fr1;
  c.distortion = {-1.2, 0, 0, 0};  // the distorted radius turns back inside the image
  EXPECT_NE(CalibrationProblem(c, {}, "x").find("folds the image"), std::string::npos);
  c = fr1;
  c.distortion = {0, 0, 0.5, 0};
  EXPECT_NE(CalibrationProblem(c, {}, "x").find("tangential"), std::string::npos);
  c = fr1;
  c.distortion = {std::nan(""), 0, 0, 0};
  EXPECT_NE(CalibrationProblem(c, {}, "x").find("not a finite number"), std::string::npos);
}

TEST(CameraFile, AbsurdCalibrationsAreRefusedNamingTheKey) {
  TempDir tmp;
  const fs::path seq = tmp.path() / "some_sequence";
  WriteTumSequence(seq, {1.0}, {1.001});
  // With an image size: refused when the file is read, at the key's line and column.
  WriteText(tmp.path() / "cx.yaml", "%YAML:1.0\nCamera.fx: 517.3\nCamera.fy: 516.5\nCamera.cx: 99999\nCamera.cy: 255.3\n"
            "Camera.width: 640\nCamera.height: 480\n");
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "cx.yaml").string()); },
                   {"cx.yaml:4:12: key 'Camera.cx'", "outside the 640x480 image"});
  WriteText(tmp.path() / "fx.yaml", "fx: 1e300\nfy: 500\ncx: 320\ncy: 240\nwidth: 640\nheight: 480\n");
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "fx.yaml").string()); }, {"fx.yaml:1:5: key 'fx'", "no focal length"});
  WriteText(tmp.path() / "k1.yaml", "fx: 500\nfy: 500\ncx: 320\ncy: 240\nwidth: 640\nheight: 480\ndistortion: [1e6, 0, 0, 0]\n");
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "k1.yaml").string()); }, {"k1.yaml:7:13: key 'distortion'", "radii"});
  // Without an image size (older ORB-SLAM2 files): refused once the images give it, before any frame.
  WriteText(tmp.path() / "orb_cy.yaml", "%YAML:1.0\nCamera.fx: 517.3\nCamera.fy: 516.5\nCamera.cx: 318.6\nCamera.cy: -3\n");
  ExpectInputError([&] { TumDatasetReader r(seq.string(), "", (tmp.path() / "orb_cy.yaml").string()); },
                   {"orb_cy.yaml:5:12: key 'Camera.cy'", "outside the 640x480 image"});
}

TEST(CameraFile, ReadsOrbSlam2AndOrbSlam3SettingsAndViquCameraYaml) {
  TempDir tmp;
  const fs::path seq = tmp.path() / "some_sequence";
  WriteTumSequence(seq, {1.0}, {1.001});
  // ORB-SLAM2 (TUM1.yaml's layout): no image size (taken from the images), distortion, depth factor.
  WriteText(tmp.path() / "orb2.yaml", "%YAML:1.0\n\n# Camera calibration\nCamera.fx: 517.306408\nCamera.fy: 516.469215\n"
            "Camera.cx: 318.643040\nCamera.cy: 255.313989\nCamera.k1: 0.262383\nCamera.k2: -0.953104\n"
            "Camera.p1: -0.005358\nCamera.p2: 0.002628\nCamera.k3: 1.163314\nCamera.fps: 30.0\nCamera.bf: 40.0\n"
            "DepthMapFactor: 5000.0\nORBextractor.nFeatures: 1000\nViewer.PointSize: 2\n");
  const TumCamera orb2 = ReadCameraFile((tmp.path() / "orb2.yaml").string());
  EXPECT_EQ(orb2.calibration.pinhole.fx, 517.306408);
  EXPECT_EQ(orb2.calibration.pinhole.cy, 255.313989);
  EXPECT_EQ(orb2.calibration.pinhole.width, 0);
  EXPECT_EQ(orb2.calibration.distortion, (std::vector<double>{0.262383, -0.953104, -0.005358, 0.002628, 1.163314}));
  EXPECT_EQ(orb2.depth_scale, 5000.0);
  EXPECT_NE(orb2.source.find("ORB-SLAM2"), std::string::npos);
  TumDatasetReader with_orb2(seq.string(), "", (tmp.path() / "orb2.yaml").string());
  EXPECT_EQ(with_orb2.intrinsics().width, 640);  // from the first image
  EXPECT_EQ(with_orb2.intrinsics().height, 480);
  EXPECT_NE(with_orb2.calibration_source().find("orb2.yaml"), std::string::npos);
  StereoFrame f;
  EXPECT_TRUE(with_orb2.Next(&f));

  // ORB-SLAM3: Camera1.*, image size, RGBD.DepthMapFactor; OpenCV matrices elsewhere are ignored.
  WriteText(tmp.path() / "orb3.yaml", "%YAML:1.0\nFile.version: \"1.0\"\nCamera.type: \"PinHole\"\nCamera1.fx: 535.4\n"
            "Camera1.fy: 539.2\nCamera1.cx: 320.1\nCamera1.cy: 247.6\nCamera1.k1: 0.0\nCamera1.k2: 0.0\n"
            "Camera1.p1: 0.0\nCamera1.p2: 0.0\nCamera.width: 640\nCamera.height: 480\nRGBD.DepthMapFactor: 1000.0\n"
            "Stereo.T_c1_c2: !!opencv-matrix\n  rows: 1\n  cols: 1\n  dt: f\n  data: [1.0]\n");
  const TumCamera orb3 = ReadCameraFile((tmp.path() / "orb3.yaml").string());
  EXPECT_EQ(orb3.calibration.pinhole.fy, 539.2);
  EXPECT_EQ(orb3.calibration.pinhole.width, 640);
  EXPECT_TRUE(HasNoDistortion(orb3.calibration));
  EXPECT_EQ(orb3.depth_scale, 1000.0);
  EXPECT_NE(orb3.source.find("ORB-SLAM3"), std::string::npos);

  // Errors name the file, line and column.
  WriteText(tmp.path() / "fisheye.yaml", "%YAML:1.0\nCamera.type: \"KannalaBrandt8\"\nCamera1.fx: 1\nCamera1.fy: 1\n"
            "Camera1.cx: 1\nCamera1.cy: 1\n");
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "fisheye.yaml").string()); },
                   {"fisheye.yaml:2:14", "only PinHole"});
  WriteText(tmp.path() / "half.yaml", "%YAML:1.0\nCamera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\n");
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "half.yaml").string()); }, {"half.yaml", "Camera.cy"});
  WriteText(tmp.path() / "neg.yaml", "%YAML:1.0\nCamera.fx: -5\nCamera.fy: 500\nCamera.cx: 320\nCamera.cy: 240\n");
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "neg.yaml").string()); }, {"neg.yaml:2:12", "Camera.fx"});
  WriteText(tmp.path() / "viqu.yaml", "fx: 500\nfy: 501\ncx: 320\ncy: 240\nwidth: 640\nheight: 480\n");
  EXPECT_EQ(ReadCameraFile((tmp.path() / "viqu.yaml").string()).calibration.pinhole.fy, 501.0);
  ExpectInputError([&] { ReadCameraFile((tmp.path() / "missing.yaml").string()); }, {"missing.yaml", "not found"});
  // Only TUM-format folders take --camera.
  ExpectInputError([&] { OpenDataset(seq.string(), DatasetFormat::kEuroc, "", (tmp.path() / "viqu.yaml").string()); },
                   {"--camera applies to TUM-format folders"});
}

}  // namespace
}  // namespace viqu::io

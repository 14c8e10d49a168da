// EurocRecorder: EuRoC MAV layout, CSV headers, sensor.yaml contents, colour order, atomicity.
#include <algorithm>
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include "common/errors.h"
#include "sim/euroc_recorder.h"
#include "slam/io/proprioception_reader.h"

namespace viqu::sim {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> ReadLines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

size_t Columns(const std::string& line) { return static_cast<size_t>(std::count(line.begin(), line.end(), ',')) + 1; }

class EurocRecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "viqu_euroc_XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
    rig_.camera.width = 32;
    rig_.camera.height = 24;
    rig_.camera.rate_hz = 20;
    rig_.intrinsics = {32, 24, 25.5, 25.5, 16.0, 12.0};
    rig_.T_body_cam0.linear() =
        Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    rig_.T_body_cam0.translation() = Eigen::Vector3d(0.1, 0.02, 0.03);
    rig_.T_body_cam1 = rig_.T_body_cam0 * Eigen::Translation3d(0.04, 0, 0);
    rig_.imu.rate_hz = 400;
    rig_.imu.gyro_noise = 0.002;
  }
  void TearDown() override { fs::remove_all(dir_); }

  StereoFrame Frame(int64_t t_ns) const {
    StereoFrame f;
    f.t_ns = t_ns;
    f.left_rgb = cv::Mat(24, 32, CV_8UC3, cv::Scalar(10, 20, 30));
    f.left_rgb.at<cv::Vec3b>(3, 2) = cv::Vec3b(255, 0, 0);  // pure red in RGB order
    f.right_rgb = cv::Mat(24, 32, CV_8UC3, cv::Scalar(0, 0, 255));  // pure blue in RGB order
    f.left_depth_m = cv::Mat(24, 32, CV_32F, cv::Scalar(1.2344f));
    f.left_depth_m.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
    f.left_depth_m.at<float>(0, 1) = 100.0f;  // beyond the 16-bit range (13.107 m)
    f.left_instance_id = cv::Mat(24, 32, CV_16U, cv::Scalar(0));
    f.left_instance_id.at<uint16_t>(5, 6) = 300;
    f.instances = {{0, Category::kBackground, "background"}, {300, Category::kPerson, "person:alice"}};
    f.intrinsics = rig_.intrinsics;
    f.baseline_m = 0.04;
    return f;
  }

  // Records 3 frames, 5 IMU samples, 2 joint states, 2 ground-truth states.
  void Record(EurocRecorder* rec) const {
    for (int i = 0; i < 3; ++i) rec->AddFrame(Frame(i * 50000000));
    for (int i = 0; i < 5; ++i) {
      ImuSample s;
      s.t_ns = i * 2500000;
      s.gyro_i = Eigen::Vector3d(0.1, 0.2, 0.3);
      s.accel_i = Eigen::Vector3d(0.0, 0.0, 9.81);
      rec->AddImu(s);
    }
    for (int i = 0; i < 2; ++i) {
      JointState j;
      j.t_ns = i * 5000000;
      j.position_rad.fill(0.5);
      j.contact = {true, false, false, true};
      rec->AddJoints(j);
      GroundTruthState g;
      g.t_ns = i * 1000000;
      g.T_w_body.p_w_x = Eigen::Vector3d(1, 2, 0.07);
      rec->AddGroundTruth(g);
    }
  }

  fs::path dir_;
  EurocRig rig_;
};

// joints0 keeps the servos' torques after the encoder columns, with the digits that read back
// exactly; a recording made before torque sensing (20 values a row) reads back without torque.
TEST_F(EurocRecorderTest, JointTorquesReadBackExactlyAndOldRecordingsHaveNone) {
  const fs::path dataset = dir_ / "dataset";
  {
    EurocRecorder rec(dataset.string(), rig_);
    for (int i = 0; i < 3; ++i) rec.AddFrame(Frame(i * 50000000));
    for (int i = 0; i < 2; ++i) {
      JointState j;
      j.t_ns = i * 5000000;
      j.position_rad.fill(0.5);
      for (int k = 0; k < kNumJoints; ++k) j.torque_nm[k] = 0.1234567890123457 * (k - 3) + 1e-7 * i;
      j.has_torque = true;
      rec.AddJoints(j);
    }
    rec.AddContact(0, {true, true, true, true}, {true, true, true, true});
    ImuSample imu;
    imu.accel_i = Eigen::Vector3d(0, 0, 9.81);
    rec.AddImu(imu);  // the reader needs one
    rec.Finish();
  }
  std::ofstream(dataset / "mav0" / "robot.urdf") << "<robot name='rat'/>\n";  // the reader needs one
  const std::optional<io::Proprioception> p = io::ReadViquProprioception(dataset.string());
  ASSERT_TRUE(p.has_value());
  ASSERT_EQ(p->joints.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_TRUE(p->joints[i].has_torque);
    for (int k = 0; k < kNumJoints; ++k) EXPECT_EQ(p->joints[i].torque_nm[k], 0.1234567890123457 * (k - 3) + 1e-7 * i);
  }
  const YAML::Node sensor = YAML::LoadFile((dataset / "mav0" / "joints0" / "sensor.yaml").string());
  EXPECT_EQ(sensor["torque_sampling"].as<std::string>(), rig_.joints.torque_sampling);
  // The same rows cut to the encoder columns, as recorded before torque sensing.
  const fs::path csv = dataset / "mav0" / "joints0" / "data.csv";
  std::ifstream in(csv);
  std::string line, old;
  while (std::getline(in, line)) {
    if (line[0] != '#') {
      size_t at = 0;
      for (int c = 0; c < 21; ++c) at = line.find(',', at + 1);
      line = line.substr(0, at);
    }
    old += line + "\n";
  }
  in.close();
  std::ofstream(csv) << old;
  const std::optional<io::Proprioception> before = io::ReadViquProprioception(dataset.string());
  ASSERT_TRUE(before.has_value());
  EXPECT_FALSE(before->joints[0].has_torque);
  EXPECT_EQ(before->joints[1].position_rad[0], 0.5);
}

TEST_F(EurocRecorderTest, WritesTheEurocLayoutOnlyOnFinish) {
  const fs::path dataset = dir_ / "dataset";
  const fs::path mav0 = dataset / "mav0";
  EurocRecorder rec(dataset.string(), rig_);
  Record(&rec);

  // Before Finish(): nothing under the final name, no CSV or YAML under its final name either.
  EXPECT_FALSE(fs::exists(dataset));
  const fs::path partial = dir_ / "dataset.partial" / "mav0";
  ASSERT_TRUE(fs::is_directory(partial));
  for (const char* f : {"cam0/data.csv", "cam1/data.csv", "imu0/data.csv", "joints0/data.csv",
                        "state_groundtruth_estimate0/data.csv", "cam0/sensor.yaml", "seg0/instances.csv",
                        "seg0/frame_instances.csv"}) {
    EXPECT_FALSE(fs::exists(partial / f)) << f;
  }
  rec.Finish();
  EXPECT_FALSE(fs::exists(dir_ / "dataset.partial"));

  for (const char* f : {"body.yaml", "cam0/sensor.yaml", "cam1/sensor.yaml", "depth0/sensor.yaml",
                        "seg0/sensor.yaml", "seg0/instances.csv", "seg0/frame_instances.csv", "imu0/sensor.yaml",
                        "joints0/sensor.yaml",
                        "state_groundtruth_estimate0/sensor.yaml"}) {
    EXPECT_TRUE(fs::is_regular_file(mav0 / f)) << f;
  }
  for (const char* cam : {"cam0", "cam1", "depth0", "seg0"}) {
    const std::vector<std::string> lines = ReadLines(mav0 / cam / "data.csv");
    ASSERT_EQ(lines.size(), 4u) << cam;
    EXPECT_EQ(lines[0], "#timestamp [ns],filename");
    EXPECT_EQ(lines[1], "0,0.png");
    EXPECT_EQ(lines[3], "100000000,100000000.png");
    EXPECT_TRUE(fs::is_regular_file(mav0 / cam / "data" / "50000000.png")) << cam;
  }
  const std::vector<std::string> imu = ReadLines(mav0 / "imu0/data.csv");
  ASSERT_EQ(imu.size(), 6u);
  EXPECT_EQ(imu[0],
            "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]");
  EXPECT_EQ(imu[2], "2500000,0.1,0.2,0.3,0,0,9.81");
  const std::vector<std::string> joints = ReadLines(mav0 / "joints0/data.csv");
  ASSERT_EQ(joints.size(), 3u);
  // Stamp, 8 positions, 8 velocities, 4 contacts, 8 torques.
  EXPECT_EQ(Columns(joints[0]), 29u);
  EXPECT_EQ(Columns(joints[1]), 29u);
  EXPECT_EQ(joints[0].rfind("#timestamp [ns],FL_hip [rad],FL_knee [rad],FR_hip [rad]", 0), 0u) << joints[0];
  EXPECT_NE(joints[0].find("BR_contact [0/1],FL_hip_torque [N m]"), std::string::npos) << joints[0];
  EXPECT_EQ(joints[1].substr(joints[1].size() - 24), ",1,0,0,1,0,0,0,0,0,0,0,0");
  // Touch sensors and planned stance, one row per encoder reading (none recorded here: header only).
  const std::vector<std::string> contact = ReadLines(mav0 / "contact0/data.csv");
  ASSERT_GE(contact.size(), 1u);
  EXPECT_EQ(contact[0].rfind("#timestamp [ns],FL_touch [0/1]", 0), 0u) << contact[0];
  EXPECT_EQ(Columns(contact[0]), 9u);
  const std::vector<std::string> gt = ReadLines(mav0 / "state_groundtruth_estimate0/data.csv");
  ASSERT_EQ(gt.size(), 3u);
  EXPECT_EQ(Columns(gt[0]), 17u);
  EXPECT_EQ(gt[0].rfind("#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x []", 0), 0u);
  EXPECT_EQ(gt[2].rfind("1000000,1.000000000,2.000000000,0.070000000,1.000000000,0.000000000", 0), 0u) << gt[2];
  EXPECT_EQ(Columns(gt[2]), 17u);
  const std::vector<std::string> inst = ReadLines(mav0 / "seg0/instances.csv");
  ASSERT_EQ(inst.size(), 3u);
  EXPECT_EQ(inst[0], "#id,category,name");
  EXPECT_EQ(inst[1], "0,background,background");
  EXPECT_EQ(inst[2], "300,person,person:alice");
  const std::vector<std::string> per_frame = ReadLines(mav0 / "seg0/frame_instances.csv");
  ASSERT_EQ(per_frame.size(), 7u);
  EXPECT_EQ(per_frame[0], "#timestamp [ns],id,category,name");
  EXPECT_EQ(per_frame[1], "0,0,background,background");
  EXPECT_EQ(per_frame[2], "0,300,person,person:alice");
  EXPECT_EQ(per_frame[6], "100000000,300,person,person:alice");
}

// A detector with wrong categories reports one id under several: every frame's list goes to
// frame_instances.csv as given, and instances.csv keeps one row per id with the category reported
// most often (of equally frequent ones, the one seen first) and the name first seen.
TEST_F(EurocRecorderTest, PerFrameInstanceListsKeepEachFramesCategories) {
  const fs::path dataset = dir_ / "dataset";
  EurocRecorder rec(dataset.string(), rig_);
  // id 300: box first, then person twice (most often), then ball.
  const Category category_300[] = {Category::kBox, Category::kPerson, Category::kPerson, Category::kPerson,
                                   Category::kBall};
  for (int i = 0; i < 5; ++i) {
    StereoFrame f = Frame(i * 50000000);
    f.instances = {{300, category_300[i], "person:alice"}, {0, Category::kBackground, "background"}};
    f.left_instance_id.at<uint16_t>(7, 7) = 9;
    // id 9: ball in frame 0, box in frame 1 (a tie: the first seen wins), then not seen.
    if (i == 0) f.instances.push_back({9, Category::kBall, "ball_9"});
    if (i == 1) f.instances.push_back({9, Category::kBox, "ball_9 renamed"});
    if (i == 2) f.instances.clear();  // latency: nothing has arrived
    rec.AddFrame(f);
  }
  rec.Finish();
  const fs::path seg0 = dataset / "mav0/seg0";
  EXPECT_EQ(ReadLines(seg0 / "instances.csv"),
            (std::vector<std::string>{"#id,category,name", "0,background,background", "9,ball,ball_9",
                                      "300,person,person:alice"}));
  EXPECT_EQ(ReadLines(seg0 / "frame_instances.csv"),
            (std::vector<std::string>{"#timestamp [ns],id,category,name",
                                      "0,300,box,person:alice",
                                      "0,0,background,background",
                                      "0,9,ball,ball_9",
                                      "50000000,300,person,person:alice",
                                      "50000000,0,background,background",
                                      "50000000,9,box,ball_9 renamed",
                                      "150000000,300,person,person:alice",
                                      "150000000,0,background,background",
                                      "200000000,300,ball,person:alice",
                                      "200000000,0,background,background"}));
  const YAML::Node y = YAML::LoadFile((seg0 / "sensor.yaml").string());
  EXPECT_EQ(y["instances"].as<std::string>(), "instances.csv");
  EXPECT_EQ(y["frame_instances"].as<std::string>(), "frame_instances.csv");
}

// A replay must project with the very doubles of the live run: intrinsics from a field of view
// (no short decimal form) and a rotated mount read back bit for bit (12 digits, as written
// before, put a replay's map points 1e-12 m off the live run's and its trajectory a printed
// digit off after some 100 frames).
TEST_F(EurocRecorderTest, SensorYamlIntrinsicsAndExtrinsicsReadBackExactly) {
  rig_.intrinsics.fx = rig_.intrinsics.fy = 16.0 / std::tan(0.5 * 1.0471975511965976);
  rig_.intrinsics.cx = 15.5 + 1.0 / 3.0;
  rig_.T_body_cam0.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  rig_.T_body_cam0.translation() = Eigen::Vector3d(0.1 / 3.0, 0.02, std::sqrt(2.0) / 10.0);
  rig_.T_body_cam1 = rig_.T_body_cam0 * Eigen::Translation3d(0.04, 0, 0);
  const fs::path dataset = dir_ / "dataset";
  EurocRecorder rec(dataset.string(), rig_);
  Record(&rec);
  rec.Finish();
  for (const char* cam : {"cam0", "cam1"}) {
    const YAML::Node y = YAML::LoadFile((dataset / "mav0" / cam / "sensor.yaml").string());
    EXPECT_EQ(y["intrinsics"].as<std::vector<double>>(),
              (std::vector<double>{rig_.intrinsics.fx, rig_.intrinsics.fy, rig_.intrinsics.cx, rig_.intrinsics.cy}));
    const std::vector<double> data = y["T_BS"]["data"].as<std::vector<double>>();
    ASSERT_EQ(data.size(), 16u);
    const Eigen::Matrix4d expected = (std::string(cam) == "cam0" ? rig_.T_body_cam0 : rig_.T_body_cam1).matrix();
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) EXPECT_EQ(data[r * 4 + c], expected(r, c)) << cam << " " << r << c;
    }
  }
}

TEST_F(EurocRecorderTest, SensorYamlHoldsIntrinsicsAndExtrinsics) {
  const fs::path dataset = dir_ / "dataset";
  EurocRecorder rec(dataset.string(), rig_);
  Record(&rec);
  rec.Finish();
  for (const char* cam : {"cam0", "cam1"}) {
    const YAML::Node y = YAML::LoadFile((dataset / "mav0" / cam / "sensor.yaml").string());
    EXPECT_EQ(y["sensor_type"].as<std::string>(), "camera");
    EXPECT_EQ(y["camera_model"].as<std::string>(), "pinhole");
    EXPECT_EQ(y["distortion_model"].as<std::string>(), "radial-tangential");
    EXPECT_DOUBLE_EQ(y["rate_hz"].as<double>(), 20);
    EXPECT_EQ(y["resolution"].as<std::vector<int>>(), (std::vector<int>{32, 24}));
    EXPECT_EQ(y["intrinsics"].as<std::vector<double>>(), (std::vector<double>{25.5, 25.5, 16.0, 12.0}));
    EXPECT_EQ(y["distortion_coefficients"].as<std::vector<double>>(), (std::vector<double>{0, 0, 0, 0}));
    EXPECT_EQ(y["T_BS"]["rows"].as<int>(), 4);
    EXPECT_EQ(y["T_BS"]["cols"].as<int>(), 4);
    const std::vector<double> data = y["T_BS"]["data"].as<std::vector<double>>();
    ASSERT_EQ(data.size(), 16u);
    const Eigen::Matrix4d expected =
        (std::string(cam) == "cam0" ? rig_.T_body_cam0 : rig_.T_body_cam1).matrix();
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(data[r * 4 + c], expected(r, c), 1e-12) << cam << " " << r << c;
    }
  }
  const YAML::Node d = YAML::LoadFile((dataset / "mav0/depth0/sensor.yaml").string());
  EXPECT_EQ(d["depth_unit_m"].as<double>(), 1.0 / 5000);  // the live depth's steps, exactly
  EXPECT_EQ(d["encoding"].as<std::string>(), "16UC1");
  const YAML::Node imu = YAML::LoadFile((dataset / "mav0/imu0/sensor.yaml").string());
  EXPECT_EQ(imu["sensor_type"].as<std::string>(), "imu");
  EXPECT_DOUBLE_EQ(imu["rate_hz"].as<double>(), 400);
  EXPECT_NEAR(imu["gyroscope_noise_density"].as<double>(), 0.002 / 20.0, 1e-12);
}

TEST_F(EurocRecorderTest, ImagesKeepColourDepthAndIds) {
  const fs::path dataset = dir_ / "dataset";
  EurocRecorder rec(dataset.string(), rig_);
  Record(&rec);
  rec.Finish();
  const fs::path mav0 = dataset / "mav0";
  const cv::Mat left = cv::imread((mav0 / "cam0/data/0.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(left.type(), CV_8UC3);
  EXPECT_EQ(left.at<cv::Vec3b>(3, 2), cv::Vec3b(0, 0, 255)) << "red in RGB must read back as red in BGR";
  EXPECT_EQ(left.at<cv::Vec3b>(0, 0), cv::Vec3b(30, 20, 10));
  const cv::Mat right = cv::imread((mav0 / "cam1/data/0.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(right.at<cv::Vec3b>(10, 10), cv::Vec3b(255, 0, 0)) << "blue in RGB must read back as blue in BGR";
  const cv::Mat depth = cv::imread((mav0 / "depth0/data/0.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth.type(), CV_16U);
  EXPECT_EQ(depth.at<uint16_t>(5, 5), 6172);  // 1.2344 m in steps of 1/5000 m
  EXPECT_EQ(depth.at<uint16_t>(0, 0), 0) << "NaN depth is written as 0";
  EXPECT_EQ(depth.at<uint16_t>(0, 1), 0) << "depth beyond 65535 / 5000 m is written as 0";
  const cv::Mat seg = cv::imread((mav0 / "seg0/data/0.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(seg.type(), CV_16U);
  EXPECT_EQ(seg.at<uint16_t>(5, 6), 300);
  EXPECT_EQ(seg.at<uint16_t>(5, 7), 0);
}

TEST_F(EurocRecorderTest, DestroyedWithoutFinishLeavesNothing) {
  {
    EurocRecorder rec((dir_ / "dataset").string(), rig_);
    Record(&rec);
  }
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(EurocRecorderTest, WithoutDepthAndSegmentationThoseFoldersAreAbsent) {
  rig_.camera.depth = false;
  rig_.camera.segmentation = false;
  EurocRecorder rec((dir_ / "dataset").string(), rig_);
  Record(&rec);
  rec.Finish();
  EXPECT_TRUE(fs::exists(dir_ / "dataset/mav0/cam0/data.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "dataset/mav0/depth0"));
  EXPECT_FALSE(fs::exists(dir_ / "dataset/mav0/seg0"));
}

TEST_F(EurocRecorderTest, FinishReplacesAnOldDataset) {
  fs::create_directories(dir_ / "dataset/mav0/old_stream");
  EurocRecorder rec((dir_ / "dataset").string(), rig_);
  Record(&rec);
  EXPECT_TRUE(fs::exists(dir_ / "dataset/mav0/old_stream"));
  rec.Finish();
  EXPECT_FALSE(fs::exists(dir_ / "dataset/mav0/old_stream"));
  EXPECT_TRUE(fs::exists(dir_ / "dataset/mav0/cam0/data.csv"));
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 1u) << "only DIR/dataset remains";
}

TEST_F(EurocRecorderTest, TimestampsMustIncrease) {
  EurocRecorder rec((dir_ / "dataset").string(), rig_);
  ImuSample s;
  s.t_ns = 10;
  s.gyro_i.setZero();
  s.accel_i.setZero();
  rec.AddImu(s);
  EXPECT_THROW(rec.AddImu(s), RunError);
  rec.AddFrame(Frame(100));
  EXPECT_THROW(rec.AddFrame(Frame(50)), RunError);
}

}  // namespace
}  // namespace viqu::sim

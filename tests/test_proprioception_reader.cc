// Reading a recording's proprioceptive streams (imu0, joints0, contact0, robot.urdf) for leg
// odometry in a replay: absent streams mean "vision only", malformed rows are bad input naming
// FILE:LINE. (That values read back exactly is held by test_scenario_slam_replay: the replay of a
// full run equals it byte for byte.)
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "common/errors.h"
#include "slam/io/imu_csv.h"
#include "slam/io/proprioception_reader.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;

class ProprioceptionReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("viqu_proprio_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "mav0");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void Write(const std::string& rel, const std::string& text) {
    fs::create_directories((dir_ / "mav0" / rel).parent_path());
    std::ofstream(dir_ / "mav0" / rel) << text;
  }
  void WriteStreams(const std::string& imu_rows) {
    Write("imu0/data.csv", "#timestamp [ns],wx,wy,wz,ax,ay,az\n" + imu_rows);
    std::string joints = "#timestamp [ns],...\n0";
    for (int i = 0; i < 16; ++i) joints += ",0.1";
    joints += ",1,0,0,1\n";
    Write("joints0/data.csv", joints);
    Write("contact0/data.csv", "#timestamp [ns],...\n0,1,0,0,1,1,1,0,0\n");
    Write("robot.urdf", "<robot name='rat'/>\n");
  }
  fs::path dir_;
};

TEST_F(ProprioceptionReaderTest, AbsentStreamsMeanVisionOnly) {
  EXPECT_FALSE(io::ReadViquProprioception(dir_.string()).has_value());
  Write("imu0/data.csv", "#t\n");
  EXPECT_FALSE(io::ReadViquProprioception(dir_.string()).has_value());  // no joints0, contact0, urdf
}

TEST_F(ProprioceptionReaderTest, AMalformedRowNamesFileAndLine) {
  WriteStreams("0,0,0,0,0,0,9.81\n5000000,0,0,nan,0,0,9.81\n");
  try {
    io::ReadViquProprioception(dir_.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("imu0/data.csv:3"), std::string::npos) << e.what();
  }
  WriteStreams("5000000,0,0,0,0,0,9.81\n5000000,0,0,0,0,0,9.81\n");  // time does not advance
  EXPECT_THROW(io::ReadViquProprioception(dir_.string()), InputError);
  WriteStreams("0,0,0,0,0,0\n");  // a field short
  EXPECT_THROW(io::ReadViquProprioception(dir_.string()), InputError);
}

TEST_F(ProprioceptionReaderTest, ImuCsvReadsEurocRowsAndRefusesAnEmptyOne) {
  // EuRoC's imu0/data.csv (what `viqu slam --format euroc` reads in mode full): gyro, then accel.
  Write("imu0/data.csv", "#timestamp [ns],wx,wy,wz,ax,ay,az\n1403636579758555392,-0.099,0.142,0.025,8.13,-0.37,-2.84\n"
                         "1403636579763555584,-0.097,0.137,0.038,8.18,-0.41,-2.87\r\n");
  const std::string path = (dir_ / "mav0" / "imu0" / "data.csv").string();
  const std::vector<ImuSample> s = io::ReadImuCsv(path);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[1].t_ns, 1403636579763555584);
  EXPECT_EQ(s[0].gyro_i, Eigen::Vector3d(-0.099, 0.142, 0.025));
  EXPECT_EQ(s[1].accel_i, Eigen::Vector3d(8.18, -0.41, -2.87));
  Write("imu0/data.csv", "#timestamp [ns],wx,wy,wz,ax,ay,az\n");
  try {
    io::ReadImuCsv(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace viqu

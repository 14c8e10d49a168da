// TrajectoryWriter: TUM lines, exact timestamps, atomic output.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "sim/trajectory_writer.h"
#include "slam/eval/trajectory.h"
#include "read_all.h"

namespace viqu::sim {
namespace {

namespace fs = std::filesystem;

using testing::ReadAll;

fs::path TempDir() {
  std::string tmpl = (fs::temp_directory_path() / "viqu_traj_XXXXXX").string();
  EXPECT_NE(::mkdtemp(tmpl.data()), nullptr);
  return tmpl;
}

TEST(TrajectoryWriter, FormatsSecondsExactly) {
  EXPECT_EQ(FormatSeconds(0), "0.000000000");
  EXPECT_EQ(FormatSeconds(12345678901), "12.345678901");
  EXPECT_EQ(FormatSeconds(50000000), "0.050000000");
  EXPECT_EQ(FormatSeconds(-1500000000), "-1.500000000");
}

TEST(TrajectoryWriter, WritesTumLinesAndRenamesOnClose) {
  const fs::path dir = TempDir();
  const fs::path path = dir / "trajectory_gt.txt";
  {
    TrajectoryWriter w(path.string());
    StampedPose p;
    p.t_ns = 1050000000;
    p.p_w_x = Eigen::Vector3d(1.0, -2.0, 0.07);
    p.q_w_x = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
    w.Add(p);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.5, 0, 0);
    w.Add(2000000000, T);
    StampedPose flipped;
    flipped.t_ns = 3000000000;
    flipped.q_w_x = Eigen::Quaterniond(-1, 0, 0, 0);
    w.Add(flipped);
    EXPECT_FALSE(fs::exists(path)) << "final name must not exist before Close()";
    EXPECT_EQ(w.size(), 3u);
    w.Close();
  }
  ASSERT_TRUE(fs::exists(path));
  EXPECT_EQ(ReadAll(path),
            "# timestamp tx ty tz qx qy qz qw\n"
            "1.050000000 1.000000000 -2.000000000 0.070000000 0.000000000 0.000000000 0.707106781 0.707106781\n"
            "2.000000000 0.500000000 0.000000000 0.000000000 0.000000000 0.000000000 0.000000000 1.000000000\n"
            "3.000000000 0.000000000 0.000000000 0.000000000 0.000000000 0.000000000 0.000000000 1.000000000\n");
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1u) << "no temporary file may be left behind";
  fs::remove_all(dir);
}

// A live run anchors its estimators at AsReadBack(truth) so that a replay, anchored at the pose
// read from the file, starts from the same bits: for poses with no short decimal form (and a
// quaternion with qw < 0), what the reader returns is AsReadBack's pose exactly.
TEST(TrajectoryWriter, AsReadBackIsExactlyWhatTheReaderGets) {
  const fs::path dir = TempDir();
  const fs::path path = dir / "trajectory_gt.txt";
  std::vector<StampedPose> poses;
  for (int i = 0; i < 20; ++i) {
    StampedPose p;
    p.t_ns = 1000000000LL * (i + 1);
    p.p_w_x = Eigen::Vector3d(1.0 / (i + 3) + 1.0 / 30000, -std::sqrt(2.0 + i), 0.07 + i / 7.0);
    p.q_w_x = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 + 0.37 * i, Eigen::Vector3d(1, i, 3).normalized()));
    if (i % 2) p.q_w_x.coeffs() = -p.q_w_x.coeffs();
    poses.push_back(p);
  }
  {
    TrajectoryWriter w(path.string());
    for (const StampedPose& p : poses) w.Add(p);
    w.Close();
  }
  const std::vector<StampedPose> read = eval::ReadTumTrajectory(path.string());
  ASSERT_EQ(read.size(), poses.size());
  int differs_from_truth = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const StampedPose a = AsReadBack(poses[i]);
    EXPECT_EQ(a.t_ns, read[i].t_ns);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.p_w_x[k], read[i].p_w_x[k]) << "pose " << i << " axis " << k;
    for (int k = 0; k < 4; ++k) EXPECT_EQ(a.q_w_x.coeffs()[k], read[i].q_w_x.coeffs()[k]) << "pose " << i << " q " << k;
    differs_from_truth += a.p_w_x != poses[i].p_w_x;
    EXPECT_LT((a.p_w_x - poses[i].p_w_x).norm(), 1e-9);
    EXPECT_LT(a.q_w_x.angularDistance(poses[i].q_w_x), 1e-8);
  }
  EXPECT_EQ(differs_from_truth, 20) << "these positions have no 9-decimal form: the rounding must show";
  fs::remove_all(dir);
}

TEST(TrajectoryWriter, DestroyedWithoutCloseLeavesNothing) {
  const fs::path dir = TempDir();
  {
    TrajectoryWriter w((dir / "trajectory_est.txt").string());
    w.Add(StampedPose{});
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace viqu::sim

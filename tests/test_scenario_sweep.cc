// `viqu sweep` end to end on tiny sweeps of short runs: a point that times out is recorded and
// the sweep goes on; --resume reruns only a point whose run folder is incomplete and gives the
// same tables; the Slurm array, run by hand task by task, gives the same results as the local
// sweep.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "common/run_folder.h"
#include "tests/viqu_program.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;
using testing::RunViqu;

const std::string kScenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
const std::string kFixed =
    "fixed: {sensors.camera.width: 320, sensors.camera.height: 240, slam.mode: visual}\n";

fs::path Fresh(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_scenario_sweep_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// results.csv rows by id, without the wall_s column (the only one that differs between runs).
std::map<std::string, std::string> ResultsWithoutWallTime(const fs::path& csv) {
  std::map<std::string, std::string> rows;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) rows[line.substr(0, line.find(','))] = line.substr(0, line.rfind(','));
  return rows;
}

TEST(Sweep, ATimedOutPointIsRecordedAndTheSweepGoesOn) {
  if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
  const fs::path dir = Fresh("timeout");
  std::ofstream(dir / "s.yaml") << "scenarios: [" + kScenario + "]\ngrid: {duration_s: [0.4, 60]}\n" + kFixed +
                                       "metrics: [ate.rmse_m]\ntimeout_s: 5\n";
  const testing::ProgramResult r = RunViqu("sweep " + (dir / "s.yaml").string() + " --out " + (dir / "out").string() + " --jobs 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string results = ReadText(dir / "out" / "results.csv");
  EXPECT_NE(results.find("p0000,static_room,1,0.4,"), std::string::npos) << results;
  EXPECT_NE(results.find(",0,ok,"), std::string::npos) << results;
  // The long point was stopped with SIGTERM: its run ended at a step boundary, exit 143.
  EXPECT_NE(results.find("p0001,static_room,1,60,,143,timeout,"), std::string::npos) << results;
  EXPECT_TRUE(fs::exists(dir / "out" / "points" / "p0001" / kRunIncompleteMarker));
  EXPECT_NE(r.output.find("1 of 2 points ok"), std::string::npos) << r.output;
}

TEST(Sweep, ResumeRerunsOnlyTheIncompletePointAndSlurmGivesTheSameResults) {
  if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
  const fs::path dir = Fresh("resume");
  std::ofstream(dir / "s.yaml") << "scenarios: [" + kScenario + "]\nseeds: [1, 2]\n"
                                   "grid: {sensors.camera.noise_std: [1, 4]}\n"
                                   "fixed: {sensors.camera.width: 320, sensors.camera.height: 240, slam.mode: visual, "
                                   "duration_s: 0.5}\nmetrics: [ate.rmse_m, tracking.frames, path_length_m]\n";
  const std::string out = (dir / "out").string();
  const testing::ProgramResult first = RunViqu("sweep " + (dir / "s.yaml").string() + " --out " + out + " --jobs 2");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto uninterrupted = ResultsWithoutWallTime(fs::path(out) / "results.csv");
  ASSERT_EQ(uninterrupted.size(), 4u);
  for (const auto& [id, row] : uninterrupted) EXPECT_NE(row.find(",0,ok"), std::string::npos) << row;

  // A point killed mid-run: only its partial folder is left (no marker), as a SIGKILL leaves it.
  const fs::path p2 = fs::path(out) / "points" / "p0002";
  fs::rename(p2, fs::path(out) / "points" / "p0002.partial-999999999");
  const auto before = fs::last_write_time(fs::path(out) / "logs" / "p0000.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const testing::ProgramResult resumed = RunViqu("sweep " + (dir / "s.yaml").string() + " --out " + out + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("4 points (3 complete already)"), std::string::npos) << resumed.output;
  EXPECT_NE(resumed.output.find("1/1 done (0 failed)"), std::string::npos) << resumed.output;
  EXPECT_EQ(fs::last_write_time(fs::path(out) / "logs" / "p0000.log"), before);  // not rerun
  EXPECT_TRUE(IsCompleteRunFolder(p2.string()));
  EXPECT_FALSE(fs::exists(fs::path(out) / "points" / "p0002.partial-999999999"));
  EXPECT_EQ(ResultsWithoutWallTime(fs::path(out) / "results.csv"), uninterrupted);
  // Without --resume, a sweep folder is not overwritten; with another grid it is not resumed.
  EXPECT_EQ(RunViqu("sweep " + (dir / "s.yaml").string() + " --out " + out).exit_code, 2);
  std::ofstream(dir / "other.yaml") << "scenarios: [" + kScenario + "]\nseeds: [1, 2]\n"
                                       "grid: {sensors.camera.noise_std: [2, 8]}\n"
                                       "fixed: {sensors.camera.width: 320, sensors.camera.height: 240, slam.mode: visual, "
                                       "duration_s: 0.5}\nmetrics: [ate.rmse_m, tracking.frames, path_length_m]\n";
  const testing::ProgramResult other = RunViqu("sweep " + (dir / "other.yaml").string() + " --out " + out + " --resume");
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("differs from the sweep"), std::string::npos) << other.output;

  // The Slurm array, every task run by hand, then --collect: the same results.
  const std::string slurm = (dir / "slurm").string();
  ASSERT_EQ(RunViqu("sweep " + (dir / "s.yaml").string() + " --out " + slurm + " --emit slurm").exit_code, 0);
  EXPECT_EQ(std::system(("bash -n " + slurm + "/sweep.sbatch").c_str()), 0);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(std::system(("SLURM_ARRAY_TASK_ID=" + std::to_string(i) + " bash " + slurm + "/sweep.sbatch").c_str()), 0) << i;
  }
  const testing::ProgramResult collected = RunViqu("sweep --collect " + slurm);
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  EXPECT_EQ(ResultsWithoutWallTime(fs::path(slurm) / "results.csv"), uninterrupted);
  EXPECT_EQ(ReadText(fs::path(slurm) / "summary.csv"), ReadText(fs::path(out) / "summary.csv"));
}

// The Slurm array keeps the sweep's time limit as the local runner does (SIGTERM at timeout_s,
// SIGKILL 10 s later) and asks Slurm for that time and two CPUs a task.
TEST(Sweep, SlurmArrayCarriesTheTimeLimit) {
  if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
  const fs::path dir = Fresh("slurm_limit");
  std::ofstream(dir / "s.yaml") << "scenarios: [" + kScenario + "]\nseeds: [1, 2]\n" + kFixed + "timeout_s: 90\n";
  const std::string out = (dir / "out").string();
  ASSERT_EQ(RunViqu("sweep " + (dir / "s.yaml").string() + " --out " + out + " --emit slurm").exit_code, 0);
  std::istringstream manifest(ReadText(fs::path(out) / "manifest.txt"));
  int lines = 0;
  for (std::string line; std::getline(manifest, line); ++lines) EXPECT_EQ(line.rfind("timeout -k 10 90 ", 0), 0u) << line;
  EXPECT_EQ(lines, 2);
  const std::string sbatch = ReadText(fs::path(out) / "sweep.sbatch");
  EXPECT_NE(sbatch.find("#SBATCH --time=3\n"), std::string::npos) << sbatch;  // 100 s, rounded up, + 1 min
  EXPECT_NE(sbatch.find("#SBATCH --cpus-per-task=2\n"), std::string::npos) << sbatch;
  EXPECT_EQ(std::system(("bash -n " + out + "/sweep.sbatch").c_str()), 0);
}

}  // namespace
}  // namespace viqu

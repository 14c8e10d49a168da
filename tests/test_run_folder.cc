// Run-folder integrity (common/run_folder.h): the completion marker, the swap that replaces a
// folder as a whole, refusals before any work, stale partial folders; and, through the program,
// re-used folders, SIGINT/SIGTERM/SIGKILL and every reader refusing an incomplete folder.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "common/run_folder.h"
#include "tests/viqu_program.h"

namespace viqu {
namespace {

namespace fs = std::filesystem;
using testing::RunViqu;

fs::path Fresh(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("viqu_run_folder_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void WriteText(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Every file under `dir` whose name marks a temporary or a partial folder.
int Debris(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") != std::string::npos || name.find(".partial") != std::string::npos) ++n;
  }
  return n;
}

TEST(RunFolder, CompleteMarkerListsEveryFileAndCatchesChanges) {
  const fs::path root = Fresh("complete");
  const std::string dir = (root / "run").string();
  {
    RunFolderWriter w(dir, false, "viqu run test");
    EXPECT_NE(w.path(), dir);
    EXPECT_FALSE(fs::exists(dir));  // nothing under the final name while the run works
    WriteText(fs::path(w.path()) / "metrics.json", "{}\n");
    WriteText(fs::path(w.path()) / "dataset" / "a.csv", "1,2\n");
    w.Complete(1);
  }
  std::string why;
  EXPECT_TRUE(IsCompleteRunFolder(dir, &why)) << why;
  const std::string marker = ReadText(fs::path(dir) / kRunCompleteMarker);
  EXPECT_NE(marker.find("\"dataset/a.csv\""), std::string::npos);
  EXPECT_NE(marker.find("\"exit_code\": 1"), std::string::npos);
  EXPECT_NE(marker.find("viqu run test"), std::string::npos);
  EXPECT_EQ(Debris(root), 0);

  WriteText(fs::path(dir) / "dataset" / "a.csv", "1,2,3\n");  // another run's file under this name
  EXPECT_FALSE(IsCompleteRunFolder(dir, &why));
  EXPECT_NE(why.find("dataset/a.csv has changed"), std::string::npos) << why;
  fs::remove(fs::path(dir) / "dataset" / "a.csv");
  EXPECT_FALSE(IsCompleteRunFolder(dir, &why));
  EXPECT_NE(why.find("dataset/a.csv is missing"), std::string::npos) << why;
  EXPECT_THROW(RequireCompleteRunFolder(dir), InputError);
  EXPECT_THROW(RequireNotInIncompleteRun(dir + "/metrics.json"), InputError);
}

TEST(RunFolder, ARerunReplacesTheWholeFolderAndAFailedOneKeepsTheOld) {
  const fs::path root = Fresh("replace");
  const std::string dir = (root / "run").string();
  {
    RunFolderWriter w(dir, false, "first");
    WriteText(fs::path(w.path()) / "trajectory_est.txt", "first\n");
    WriteText(fs::path(w.path()) / "metrics.json", "{\"first\": 1}\n");
    w.Complete(0);
  }
  {
    // A run that fails (an exception before Complete) leaves the earlier run as it was.
    RunFolderWriter w(dir, false, "failed");
    WriteText(fs::path(w.path()) / "metrics.json", "{\"failed\": 1}\n");
  }
  EXPECT_TRUE(IsCompleteRunFolder(dir));
  EXPECT_EQ(ReadText(fs::path(dir) / "metrics.json"), "{\"first\": 1}\n");
  {
    RunFolderWriter w(dir, false, "second");
    WriteText(fs::path(w.path()) / "metrics.json", "{\"second\": 1}\n");
    w.Complete(0);
  }
  EXPECT_TRUE(IsCompleteRunFolder(dir));
  EXPECT_FALSE(fs::exists(fs::path(dir) / "trajectory_est.txt"));  // the first run's file is gone
  EXPECT_EQ(ReadText(fs::path(dir) / "metrics.json"), "{\"second\": 1}\n");
  EXPECT_EQ(Debris(root), 0);
}

// A real run's folder (the stored one of a `full` run, tests/data/report_run) is replaced by a
// rerun without --force: every file a run writes is one the writer knows as its own.
TEST(RunFolder, ARealRunsFolderIsReplacedWithoutForce) {
  const fs::path root = Fresh("real");
  const fs::path dir = root / "run";
  fs::copy(fs::path(VIQU_SOURCE_DIR) / "tests" / "data" / "report_run", dir, fs::copy_options::recursive);
  ASSERT_TRUE(fs::exists(dir / "contact.csv"));
  ASSERT_TRUE(IsCompleteRunFolder(dir.string()));
  {
    RunFolderWriter w(dir.string(), false, "rerun");
    WriteText(fs::path(w.path()) / "metrics.json", "{\"rerun\": 1}\n");
    w.Complete(0);
  }
  EXPECT_FALSE(fs::exists(dir / "contact.csv"));
  EXPECT_EQ(ReadText(dir / "metrics.json"), "{\"rerun\": 1}\n");
}

TEST(RunFolder, InterruptedFolderIsRefusedWithItsReason) {
  const fs::path root = Fresh("interrupted");
  const std::string dir = (root / "run").string();
  {
    RunFolderWriter w(dir, false, "viqu run x");
    WriteText(fs::path(w.path()) / "trajectory_gt.txt", "0 0 0 0 0 0 0 1\n");
    w.Interrupted("SIGINT at simulated time 3.000 s of 10.000 s");
  }
  std::string why;
  EXPECT_FALSE(IsCompleteRunFolder(dir, &why));
  EXPECT_NE(why.find("SIGINT at simulated time 3.000 s"), std::string::npos) << why;
  EXPECT_TRUE(LooksLikeRunFolder(dir));
  try {
    RequireNotInIncompleteRun(dir + "/trajectory_gt.txt");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("which is incomplete or was changed after the run"), std::string::npos) << e.what();
  }
}

TEST(RunFolder, RefusesBadOutputFoldersBeforeAnyWork) {
  const fs::path root = Fresh("refuse");
  WriteText(root / "a_file", "x");
  EXPECT_THROW(RunFolderWriter((root / "a_file").string(), true, ""), InputError);
  // A folder of the user's that holds no viqu run: refused unless forced.
  WriteText(root / "mine" / "notes.txt", "keep me");
  EXPECT_THROW(RunFolderWriter((root / "mine").string(), false, ""), InputError);
  EXPECT_EQ(ReadText(root / "mine" / "notes.txt"), "keep me");
  {
    RunFolderWriter forced((root / "mine").string(), true, "");
    forced.Complete(0);
  }
  EXPECT_FALSE(fs::exists(root / "mine" / "notes.txt"));
  // A folder that holds a scenario file and notes of the user's is no run folder: refused.
  WriteText(root / "experiment" / "scenario.yaml", "name: x\n");
  WriteText(root / "experiment" / "notes.md", "keep me");
  EXPECT_THROW(RunFolderWriter((root / "experiment").string(), false, ""), InputError);
  // Inputs inside the output folder are refused (the folder is replaced as a whole).
  EXPECT_THROW(RequireOutsideOutput((root / "experiment").string(), (root / "experiment" / "scenario.yaml").string()), InputError);
  EXPECT_NO_THROW(RequireOutsideOutput((root / "experiment").string(), (root / "mine" / "x.yaml").string()));
  // ... and --force does not lift that: the writer checks its inputs before anything else. Nor
  // may the output folder lie inside an input folder (a recorded run replayed into its own
  // dataset/ would be replaced by the replay).
  try {
    RunFolderWriter forced((root / "experiment").string(), true, "", {(root / "experiment" / "scenario.yaml").string()});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds the input"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("--force"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadText(root / "experiment" / "scenario.yaml"), "name: x\n");
  WriteText(root / "recorded" / "dataset" / "mav0" / "imu0.csv", "t\n");
  try {
    RunFolderWriter forced((root / "recorded" / "dataset").string(), true, "", {(root / "recorded").string()});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lies inside the input folder"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadText(root / "recorded" / "dataset" / "mav0" / "imu0.csv"), "t\n");
  EXPECT_NO_THROW(RequireOutsideOutput((root / "recorded_replay").string(), (root / "recorded").string()));
  // A relative --out whose first folder does not exist yet, given from inside the input folder
  // (`cd dataset && viqu slam . --format euroc` writes runs/slam-. by default).
  const fs::path cwd = fs::current_path();
  fs::current_path(root / "recorded");
  EXPECT_THROW(RequireOutsideOutput("runs/slam-x", (root / "recorded").string()), InputError);
  EXPECT_THROW(RequireOutsideOutput("runs/slam-x", "."), InputError);
  fs::current_path(cwd);
  // The current folder (or one above it) is never replaced, forced or not.
  EXPECT_THROW(RunFolderWriter(fs::current_path().string(), true, ""), InputError);
  EXPECT_THROW(RunFolderWriter(fs::current_path().parent_path().string(), true, ""), InputError);
  // An unwritable parent (root ignores permissions, so only where they apply).
  if (::geteuid() != 0) {
    fs::create_directories(root / "locked");
    fs::permissions(root / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(RunFolderWriter((root / "locked" / "run").string(), false, ""), InputError);
    fs::permissions(root / "locked", fs::perms::owner_all);
  }
}

TEST(RunFolder, TheOutputsLineListsWhatTheFolderHolds) {
  const fs::path root = Fresh("outputs_line");
  WriteText(root / "run" / "metrics.json", "{}");
  WriteText(root / "run" / "lo.csv", "t\n");
  WriteText(root / "run" / "dataset" / "mav0" / "x", "");
  EXPECT_EQ(OutputsLine((root / "run").string()), (root / "run").string() + "/{dataset/,lo.csv,metrics.json}");
}

TEST(RunFolder, StalePartialFoldersOfDeadProcessesAreRemoved) {
  const fs::path root = Fresh("stale");
  // A process that has ended: its PID names a partial folder no one will finish.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const fs::path stale = root / ("run.partial-" + std::to_string(dead));
  const fs::path alive = root / ("run.partial-" + std::to_string(::getppid()));
  WriteText(stale / "scenario.yaml", "half");
  WriteText(alive / "scenario.yaml", "another run still writing");
  {
    RunFolderWriter w((root / "run").string(), false, "");
    w.Complete(0);
  }
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(alive));
  // A partial folder is recognisably incomplete to every reader.
  EXPECT_THROW(RequireNotInIncompleteRun((alive / "scenario.yaml").string()), InputError);
}

// A run killed between the swap's two renames: DIR is missing, its result is complete in the
// partial folder (or the previous run sits in DIR.old.PID). The next run puts it back, not away.
TEST(RunFolder, ASwapCutShortIsRepairedByTheNextRun) {
  const fs::path root = Fresh("swap_cut");
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  {
    RunFolderWriter w((root / "run").string(), false, "finished");
    WriteText(fs::path(w.path()) / "metrics.json", "{\"finished\": 1}\n");
    w.Complete(0);
  }
  fs::rename(root / "run", root / ("run.partial-" + std::to_string(dead)));
  {
    // A run into another folder beside it leaves it alone; one into DIR repairs it first, and a
    // failed one (no Complete) keeps the repaired result.
    RunFolderWriter w((root / "run").string(), false, "failed");
  }
  EXPECT_TRUE(IsCompleteRunFolder((root / "run").string()));
  EXPECT_EQ(ReadText(root / "run" / "metrics.json"), "{\"finished\": 1}\n");
  fs::rename(root / "run", root / ("run.old." + std::to_string(dead)));
  { RunFolderWriter w((root / "run").string(), false, "failed"); }
  EXPECT_TRUE(IsCompleteRunFolder((root / "run").string()));
  EXPECT_EQ(Debris(root), 0);
}

// ---- Through the program -------------------------------------------------------------------

const std::string kScenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";
// A small, short run: 320x240 images.
const std::string kSmall = " --set sensors.camera.width=320 --set sensors.camera.height=240";

TEST(RunFolderProgram, ReusedFolderNeverMixesRuns) {
  if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
  const fs::path root = Fresh("reuse");
  const std::string d = (root / "D").string();
  ASSERT_EQ(RunViqu("run " + kScenario + " --out " + d + kSmall + " --set duration_s=1 --record").exit_code, 0);
  ASSERT_TRUE(fs::exists(fs::path(d) / "dataset"));
  const testing::ProgramResult second =
      RunViqu("run " + kScenario + " --out " + d + kSmall + " --set duration_s=0.5 --set robot.start.xy=[0.5,0.5] --no-slam");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(IsCompleteRunFolder(d));
  for (const char* gone : {"dataset", "trajectory_est.txt", "tracking.csv", "slam_settings.yaml", "lo.csv"}) {
    EXPECT_FALSE(fs::exists(fs::path(d) / gone)) << gone << " of the first run is still there";
  }
  // The replay finds no recording instead of reading the first run's against the second's truth.
  const testing::ProgramResult replay = RunViqu("slam " + d + " --out " + (root / "S").string());
  EXPECT_EQ(replay.exit_code, 2) << replay.output;
  // A re-run that fails on bad input leaves the folder as it was.
  const std::string before = ReadText(fs::path(d) / "metrics.json");
  EXPECT_EQ(RunViqu("run " + kScenario + " --out " + d + " --set duration_s=-1").exit_code, 2);
  EXPECT_EQ(ReadText(fs::path(d) / "metrics.json"), before);
  EXPECT_EQ(Debris(root), 0);
}

// Starts a run into `out`, waits until its partial folder has its first outputs, sends `signal`.
int SignalledRun(const fs::path& out, int signal, const fs::path& log) {
  const pid_t pid = testing::SpawnViqu({"run", kScenario, "--out", out.string(), "--set", "sensors.camera.width=320",
                                        "--set", "sensors.camera.height=240", "--set", "duration_s=60", "--record"},
                                       log.string());
  if (pid <= 0) return -1;
  const fs::path partial = out.string() + ".partial-" + std::to_string(pid);
  for (int i = 0; i < 600 && !fs::exists(partial / "dataset.partial"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // some frames
  ::kill(pid, signal);
  return testing::WaitViqu(pid);
}

TEST(RunFolderProgram, InterruptsMarkTheFolderIncompleteAndEveryReaderRefusesIt) {
  if (!testing::ViquBuilt()) GTEST_SKIP() << "the viqu program is not built";
  const fs::path root = Fresh("signals");
  for (const auto& [signal, code] : {std::pair{SIGINT, 130}, std::pair{SIGTERM, 143}}) {
    const fs::path d = root / ("D" + std::to_string(signal));
    EXPECT_EQ(SignalledRun(d, signal, root / "log.txt"), code) << ReadText(root / "log.txt");
    ASSERT_TRUE(fs::exists(d / kRunIncompleteMarker)) << ReadText(root / "log.txt");
    EXPECT_FALSE(fs::exists(d / kRunCompleteMarker));
    EXPECT_TRUE(fs::exists(d / "dataset" / "mav0"));  // the outputs so far are flushed, to look at
    EXPECT_EQ(Debris(root), 0) << "temporaries or partial folders left";
    const testing::ProgramResult replay = RunViqu("slam " + d.string() + " --out " + (root / "S").string());
    EXPECT_EQ(replay.exit_code, 2) << replay.output;
    EXPECT_NE(replay.output.find("which is incomplete or was changed after the run"), std::string::npos) << replay.output;
    EXPECT_EQ(RunViqu("slam " + (d / "dataset").string() + " --format euroc --out " + (root / "S").string()).exit_code, 2);
    const testing::ProgramResult eval =
        RunViqu("eval " + (d / "trajectory_est.txt").string() + " " + (d / "trajectory_gt.txt").string());
    EXPECT_EQ(eval.exit_code, 2) << eval.output;
    EXPECT_FALSE(fs::exists(root / "S"));
  }
  // SIGKILL: the final name is never written; the partial folder is refused by the readers and
  // removed by the next run into the same folder.
  const fs::path k = root / "K";
  EXPECT_EQ(SignalledRun(k, SIGKILL, root / "log.txt"), 128 + SIGKILL);
  EXPECT_FALSE(fs::exists(k));
  fs::path partial;
  for (const auto& e : fs::directory_iterator(root)) {
    if (e.path().filename().string().rfind("K.partial-", 0) == 0) partial = e.path();
  }
  ASSERT_FALSE(partial.empty());
  EXPECT_EQ(RunViqu("slam " + partial.string() + " --out " + (root / "S").string()).exit_code, 2);
  EXPECT_EQ(RunViqu("eval " + (partial / "trajectory_gt.txt").string() + " " + (partial / "trajectory_gt.txt").string()).exit_code, 2);
  ASSERT_EQ(RunViqu("run " + kScenario + " --out " + k.string() + kSmall + " --set duration_s=0.2 --no-slam").exit_code, 0);
  EXPECT_FALSE(fs::exists(partial));
  EXPECT_TRUE(IsCompleteRunFolder(k.string()));
}

}  // namespace
}  // namespace viqu

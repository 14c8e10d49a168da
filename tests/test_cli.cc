// Command-line parsing of every subcommand of DESIGN.md.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/cli.h"
#include "apps/usage_error.h"

namespace viqu::app {
namespace {

CliArgs Parse(std::vector<const char*> args) {
  args.insert(args.begin(), "viqu");
  return ParseCommandLine(static_cast<int>(args.size()), args.data());
}

std::string UsageErrorOf(std::vector<const char*> args) {
  try {
    Parse(std::move(args));
  } catch (const UsageError& e) {
    return e.what();
  }
  return "<no UsageError>";
}

TEST(Cli, RunWithAllOptions) {
  const CliArgs a = Parse({"run", "scenarios/static_room.yaml", "--out", "runs/x", "--set",
                           "sensors.camera.rate_hz=10", "--set=obstacles=[]", "--no-slam", "--record", "--video"});
  ASSERT_EQ(a.command, Command::kRun);
  EXPECT_EQ(a.run.scenario, "scenarios/static_room.yaml");
  EXPECT_EQ(a.run.options.out_dir, "runs/x");
  EXPECT_EQ(a.run.sets, (std::vector<std::string>{"sensors.camera.rate_hz=10", "obstacles=[]"}));
  EXPECT_FALSE(a.run.options.slam);
  EXPECT_TRUE(a.run.options.record);
  EXPECT_TRUE(a.run.options.video);
}

TEST(Cli, RunDefaults) {
  const CliArgs a = Parse({"run", "s.yaml"});
  EXPECT_TRUE(a.run.options.out_dir.empty());
  EXPECT_TRUE(a.run.options.slam);
  EXPECT_FALSE(a.run.options.record);
  EXPECT_FALSE(a.run.options.video);
  EXPECT_TRUE(a.run.sets.empty());
  // Options may come before the scenario; values may start with '-'.
  const CliArgs b = Parse({"run", "--out=o", "--set", "robot.start.yaw_deg=-30", "s.yaml"});
  EXPECT_EQ(b.run.scenario, "s.yaml");
  EXPECT_EQ(b.run.options.out_dir, "o");
  EXPECT_EQ(b.run.sets, (std::vector<std::string>{"robot.start.yaw_deg=-30"}));
}

TEST(Cli, OtherSubcommandsParseTheirOptions) {
  const CliArgs s = Parse({"slam", "runs/x", "--format", "euroc", "--config", "c.yaml", "--out", "o"});
  ASSERT_EQ(s.command, Command::kSlam);
  EXPECT_EQ(s.slam.dataset_dir, "runs/x");
  EXPECT_EQ(s.slam.format, "euroc");
  EXPECT_EQ(s.slam.config, "c.yaml");
  EXPECT_EQ(s.slam.out_dir, "o");
  EXPECT_EQ(Parse({"slam", "d"}).slam.format, "viqu");

  const CliArgs e = Parse({"eval", "est.txt", "gt.txt", "--json"});
  ASSERT_EQ(e.command, Command::kEval);
  EXPECT_EQ(e.eval.estimate, "est.txt");
  EXPECT_EQ(e.eval.ground_truth, "gt.txt");
  EXPECT_TRUE(e.eval.json);

  const CliArgs w = Parse({"sweep", "sweep.yaml", "--jobs", "4"});
  ASSERT_EQ(w.command, Command::kSweep);
  EXPECT_EQ(w.sweep.sweep_file, "sweep.yaml");
  EXPECT_EQ(w.sweep.jobs, 4);

  const CliArgs v = Parse({"view", "s.yaml", "--set", "seed=3"});
  ASSERT_EQ(v.command, Command::kView);
  EXPECT_EQ(v.view.scenario, "s.yaml");
  EXPECT_EQ(v.view.sets, (std::vector<std::string>{"seed=3"}));
}

TEST(Cli, Help) {
  EXPECT_EQ(Parse({"--help"}).command, Command::kHelp);
  EXPECT_EQ(Parse({"--help"}).help_topic, "");
  const CliArgs r = Parse({"run", "--help"});
  EXPECT_EQ(r.command, Command::kHelp);
  EXPECT_EQ(r.help_topic, "run");
  EXPECT_EQ(Parse({"help", "eval"}).help_topic, "eval");
  EXPECT_NE(UsageText().find("viqu run SCENARIO.yaml"), std::string::npos);
  EXPECT_NE(UsageText().find("viqu sweep SWEEP.yaml [--jobs N]"), std::string::npos);
  EXPECT_NE(UsageText("run").find("--no-slam"), std::string::npos);
}

TEST(Cli, UsageErrors) {
  EXPECT_EQ(UsageErrorOf({}), "missing command");
  EXPECT_EQ(UsageErrorOf({"fly"}), "unknown command 'fly'");
  EXPECT_EQ(UsageErrorOf({"run"}), "run: missing SCENARIO.yaml");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "b.yaml"}), "run: unexpected argument 'b.yaml'");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--out"}), "run: option --out needs a value");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--fast"}), "run: unknown option --fast");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--record=yes"}), "run: option --record takes no value");
  EXPECT_EQ(UsageErrorOf({"run", "a.yaml", "--set", "duty"}), "run: --set expects key.path=value, got 'duty'");
  EXPECT_EQ(UsageErrorOf({"slam", "d", "--format", "kitti"}),
            "slam: --format expects viqu, euroc or tum, got 'kitti'");
  EXPECT_EQ(UsageErrorOf({"eval", "est.txt"}), "eval: missing GT.txt");
  EXPECT_EQ(UsageErrorOf({"sweep", "s.yaml", "--jobs", "0"}),
            "sweep: --jobs expects a whole number from 1 to 1024, got '0'");
  EXPECT_EQ(UsageErrorOf({"help", "fly"}), "help: unknown command 'fly'");
}

// The program's exit codes and messages (DESIGN.md): 0 ok, 2 bad input or usage.
struct ProgramResult {
  int exit_code = -1;  // process exit status
  std::string output;  // stdout and stderr together
};

ProgramResult RunViqu(const std::string& args) {
  ProgramResult r;
  const std::string cmd = std::string(VIQU_BINARY_DIR) + "/apps/viqu " + args + " 2>&1";
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[512];
  for (size_t n; (n = std::fread(buf, 1, sizeof(buf), p)) > 0;) r.output.append(buf, n);
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(CliProgram, ExitCodesAndMessages) {
  if (!std::filesystem::exists(std::string(VIQU_BINARY_DIR) + "/apps/viqu")) {
    GTEST_SKIP() << "the viqu program is not built";
  }
  EXPECT_EQ(RunViqu("--help").exit_code, 0);
  const ProgramResult none = RunViqu("");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.output.find("usage: viqu COMMAND"), std::string::npos) << none.output;
  const ProgramResult missing = RunViqu("run /nonexistent/scenario.yaml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.output, "viqu: /nonexistent/scenario.yaml: file not found\n");

  const std::string dir = ::testing::TempDir() + "viqu_cli_bad";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/bad.yaml") << "name: x\nworld: [oops\n";
  const ProgramResult malformed = RunViqu("run " + dir + "/bad.yaml");
  EXPECT_EQ(malformed.exit_code, 2);
  EXPECT_EQ(malformed.output.rfind("viqu: " + dir + "/bad.yaml:3:1: YAML syntax error", 0), 0u) << malformed.output;
  std::filesystem::remove_all(dir);

  const ProgramResult later = RunViqu("sweep s.yaml --jobs 2");
  EXPECT_EQ(later.exit_code, 2);
  EXPECT_EQ(later.output, "viqu: 'sweep' is not implemented yet\n");
}

}  // namespace
}  // namespace viqu::app

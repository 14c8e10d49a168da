// The `viqu` command-line program: parses the command line, loads the inputs and hands them to
// the libraries. Exit codes (DESIGN.md): 0 ok, 1 run failed, 2 bad input or usage.
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <string>

#include "apps/cli.h"
#include "apps/eval_command.h"
#include "runner/run_options.h"
#include "runner/run_scenario.h"
#include "apps/report_command.h"
#include "apps/slam_command.h"
#include "apps/sweep_command.h"
#include "apps/usage_error.h"
#include "apps/view_command.h"
#include "common/errors.h"
#include "common/stop_signal.h"
#include "scenario/scenario_loader.h"
#include "slam/settings/slam_settings.h"
#include "viqu_version.h"  // generated at build time (cmake/write_version.cmake)

namespace viqu::app {
namespace {

constexpr int kExitOk = 0;
constexpr int kExitRunFailed = 1;
constexpr int kExitBadInput = 2;

// This program's own file: sweeps start it once per point.
std::string SelfPath() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) throw RunError("cannot find the viqu program's own path (/proc/self/exe)");
  return std::string(buf, static_cast<size_t>(n));
}

// A scenario refused a --set: when its key is a SLAM setting (`viqu slam`'s form, dynamic.method),
// the message says the scenario's form (slam.dynamic.method).
Scenario LoadScenarioOrSuggest(const RunArgs& args) {
  try {
    return LoadScenario(args.scenario, args.sets);
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const std::string& set : args.sets) {
      if (what.rfind("--set " + set + ":", 0) != 0 || what.find("unknown key") == std::string::npos) continue;
      try {
        slam::LoadSlamSettings(slam::DefaultSlamSettingsPath(), {set});
      } catch (const InputError&) {
        break;  // no SLAM setting either
      }
      throw InputError(what + "; it is a SLAM setting: viqu run takes it as --set slam." + set);
    }
    throw;
  }
}

int Run(const RunArgs& args, const std::string& command_line) {
  const Scenario scenario = LoadScenarioOrSuggest(args);
  runner::RunOptions options = args.options;
  options.command_line = command_line;
  if (options.out_dir.empty()) options.out_dir = "runs/" + scenario.name;
  const int code = runner::RunScenario(scenario, options);
  if (options.report && (code == 0 || code == 1)) {
    const int report = RunReport(options.out_dir, {});
    if (report != 0) std::fprintf(stderr, "viqu: the report failed (exit %d); the run folder is complete\n", report);
  }
  return code;
}

int Dispatch(const CliArgs& args) {
  switch (args.command) {
    case Command::kHelp:
      std::fputs(UsageText(args.help_topic).c_str(), stdout);
      return kExitOk;
    case Command::kVersion:
      std::printf("viqu %s (git %s)\n", VIQU_VERSION, VIQU_GIT_COMMIT);
      return kExitOk;
    case Command::kRun: return Run(args.run, args.command_line);
    case Command::kSlam: return RunSlamCommand(args.slam, args.command_line);
    case Command::kEval: return RunEval(args.eval);
    case Command::kSweep: return RunSweepCommand(args.sweep, SelfPath());
    case Command::kReport: return RunReport(args.report.dir, args.report.tool_args);
    case Command::kView: return RunViewCommand(args.view, args.command_line);
  }
  return kExitBadInput;
}

int Main(int argc, const char* const argv[]) {
  // SIGINT/SIGTERM stop a run at a frame boundary with its folder marked incomplete.
  InstallStopSignalHandlers();
  try {
    return Dispatch(ParseCommandLine(argc, argv));
  } catch (const UsageError& e) {
    // A command's own errors start with its name ("eval: ..."): point at its help, so that the
    // message is not scrolled away by every command's usage.
    const std::string what = e.what();
    const std::string command = what.substr(0, what.find(':'));
    if (what.find(':') != std::string::npos && !UsageText(command).empty()) {
      std::fprintf(stderr, "viqu: %s\n(viqu %s --help lists its options)\n", what.c_str(), command.c_str());
    } else {
      std::fprintf(stderr, "viqu: %s\n\n%s", what.c_str(), UsageText().c_str());
    }
    return kExitBadInput;
  } catch (const InputError& e) {
    std::fprintf(stderr, "viqu: %s\n", e.what());
    return kExitBadInput;
  } catch (const Stopped& e) {
    std::fprintf(stderr, "viqu: %s; nothing written\n", e.what());
    return ExitCodeForSignal(e.signal());
  } catch (const RunError& e) {
    std::fprintf(stderr, "viqu: run failed: %s\n", e.what());
    return kExitRunFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "viqu: internal error: %s\n", e.what());
    return kExitRunFailed;
  }
}

}  // namespace
}  // namespace viqu::app

int main(int argc, char** argv) { return viqu::app::Main(argc, argv); }

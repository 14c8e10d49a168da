#include "apps/cli.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <algorithm>
#include <set>
#include <thread>
#include <utility>

#include "apps/usage_error.h"

namespace viqu::app {
namespace {

// The largest RPE frame distance --delta accepts: no trajectory of a run is longer.
constexpr long long kMaxDeltaFrames = 1'000'000;

const char* const kRunUsage =
    "viqu run SCENARIO.yaml [--out DIR] [--force] [--set key.path=value ...] [--no-slam] [--record] [--record-tum]\n"
    "         [--video] [--report] [--sequential]\n"
    "    simulate the scenario, run SLAM live and write the run folder (default runs/NAME)\n"
    "    --out DIR        run folder; replaced as a whole when the run ends (an earlier run there is gone)\n"
    "    --force          let --out replace a non-empty folder that holds no viqu run\n"
    "    --set K=V        override a scenario key (repeatable), e.g. --set sensors.camera.rate_hz=10\n"
    "    --no-slam        simulate and record ground truth only\n"
    "    --record         also write an EuRoC-layout dataset under DIR/dataset\n"
    "    --record-tum     also write a TUM RGB-D dataset of the left camera under DIR/dataset_tum\n"
    "    --video          also write DIR/video.mp4\n"
    "    --report         also plot the run into DIR/plots (viqu report)\n"
    "    --sequential     run the estimator on the simulation's thread instead of beside it (the same\n"
    "                     outputs, slower: for comparison and profiling)\n";
const char* const kSlamUsage =
    "viqu slam DATASET_DIR [--format viqu|euroc|tum] [--config FILE] [--camera FILE] [--out DIR] [--force]\n"
    "          [--masks DIR] [--skip-bad-frames [N]] [--set key.path=value ...]\n"
    "    replay a recorded run folder or a public dataset through SLAM\n"
    "    --format F       viqu (a run folder written with --record; default), euroc (EuRoC MAV,\n"
    "                     rectified on reading), tum (TUM RGB-D; tracks in rgbd mode)\n"
    "    --config FILE    SLAM settings (default slam/config/default.yaml)\n"
    "    --camera FILE    camera calibration: viqu's camera.yaml or an ORB-SLAM2/ORB-SLAM3 settings file\n"
    "                     (Camera.fx... or Camera1.fx...); for a TUM folder without camera.yaml it is needed\n"
    "                     unless the folder name says freiburg1/2/3\n"
    "    --out DIR        output folder (default runs/slam-<dataset folder name>), replaced as a whole\n"
    "    --force          let --out replace a non-empty folder that holds no viqu run\n"
    "    --masks DIR      per-frame 16-bit instance PNGs named like the images, plus\n"
    "                     DIR/instances.csv (id,category,name); see docs/MASKS.md\n"
    "    --skip-bad-frames [N]  skip up to N (default 1) lone frames whose images cannot be read\n"
    "                     (warned, counted in metrics.json camera.frames_skipped) instead of stopping\n"
    "                     with exit 2; two unreadable frames in a row, or the first, still stop it\n"
    "    --set K=V        override a SLAM settings key (repeatable), e.g. --set tracking.min_inliers=40;\n"
    "                     the scenario form slam.K=V (as viqu run --set takes it) is read the same\n";
const char* const kEvalUsage =
    "viqu eval EST.txt GT.txt [--json] [--sim3] [--delta N | --delta-m D]\n"
    "    ATE and RPE of an estimated trajectory against the ground truth, as TUM's evaluate_ate.py and\n"
    "    evaluate_rpe.py compute them. Both files in TUM format: one pose a line, 't tx ty tz qx qy qz qw'\n"
    "    (seconds, metres, unit quaternion; spaces, tabs or commas between; '#' lines skipped). Poses are\n"
    "    associated by time within 0.02 s; the estimate is aligned to the truth by Umeyama's method.\n"
    "    --json           print the ate.* and rpe.* keys of metrics.json as one JSON object\n"
    "    --sim3           align with a similarity (a scale too; printed): for monocular estimates\n"
    "    --delta N        RPE over pairs N associated poses apart (default 1)\n"
    "    --delta-m D      RPE over pairs D metres of ground-truth path apart\n"
    "    exit 2 naming FILE:LINE for a malformed, non-finite, repeated or backward pose, an empty or\n"
    "    unreadable file, fewer than 3 associated poses, or an RPE distance that gives no pair\n";
const char* const kSweepUsage =
    "viqu sweep SWEEP.yaml [--jobs N] [--out DIR] [--resume] [--emit slurm|list]\n"
    "viqu sweep --collect DIR\n"
    "    run a parameter grid over scenarios and seeds, one `viqu run` per point (docs: README, Sweeps)\n"
    "    --jobs N         points at once (default: the number of cores)\n"
    "    --out DIR        sweep folder (default sweeps/<sweep file name>): points/, logs/, results.csv, summary.csv\n"
    "    --resume         skip points whose run folder is complete\n"
    "    --emit slurm     write DIR/manifest.txt and DIR/sweep.sbatch (a Slurm job array) instead of running\n"
    "    --emit list      write DIR/manifest.txt only (for GNU parallel and the like)\n"
    "    --collect DIR    build the tables from the points finished so far\n";
const char* const kReportUsage =
    "viqu report DIR [--x KEY] [--y KEY] [--metric M]\n"
    "    plots (matplotlib, headless) into DIR/plots: for a run folder the top view, the error over\n"
    "    time and the dynamic-object timeline; for a sweep folder a heatmap of M over the grid keys\n"
    "    --x and --y, or a line over --x with the seeds' spread\n";
const char* const kViewUsage =
    "viqu view SCENARIO.yaml [--out DIR] [--force] [--set key.path=value ...] [--no-slam] [--speed X]\n"
    "          [--paused] [--exit-at-end] [--screenshot FILE]\n"
    "    run the scenario as `viqu run` does (same run folder, default runs/<name>-view) and show it\n"
    "    in a window (GLFW; needs a display): the world from a camera following the robot, the\n"
    "    ground-truth and SLAM paths, the map points, the camera image with SLAM's overlays\n"
    "    --speed X        simulated seconds per second (default 1; 0: as fast as it runs)\n"
    "    --paused         start paused (space resumes, n steps one frame)\n"
    "    --exit-at-end    close the window when the run ends (default: it stays until closed)\n"
    "    --screenshot F   write the window's last picture to F (PNG) when the viewer ends\n";

// The whole of `text` as a finite number; nothing when it is not one.
std::optional<double> FiniteNumber(const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(x)) return std::nullopt;
  return x;
}

// Walks over one subcommand's arguments: options (with values) and positionals.
class ArgCursor {
 public:
  ArgCursor(int argc, const char* const argv[], int first, std::string command)
      : argc_(argc), argv_(argv), i_(first), command_(std::move(command)) {}

  bool Done() const { return i_ >= argc_; }
  // The next argument; for "--name=value" splits off the value (see TakeValue). An option other
  // than --set given a second time is a usage error: which of the two was meant is not for the
  // program to guess (`--out A --out B` took B silently).
  std::string Next() {
    std::string arg = argv_[i_++];
    pending_value_.clear();
    has_pending_ = false;
    if (arg.size() > 2 && arg.compare(0, 2, "--") == 0) {
      const size_t eq = arg.find('=');
      if (eq != std::string::npos) {
        pending_value_ = arg.substr(eq + 1);
        has_pending_ = true;
        arg = arg.substr(0, eq);
      }
      if (arg != "--set" && !seen_.insert(arg).second) {
        throw UsageError(command_ + ": option " + arg + " given twice");
      }
    }
    return arg;
  }
  // With "--name=value" that value; else the next argument when it is a whole number (taken);
  // else nothing (the option stands alone).
  std::optional<std::string> TakeOptionalNumber() {
    if (has_pending_) {
      has_pending_ = false;
      return pending_value_;
    }
    if (i_ < argc_) {
      const std::string next = argv_[i_];
      if (!next.empty() && next.find_first_not_of("0123456789") == std::string::npos) {
        ++i_;
        return next;
      }
    }
    return std::nullopt;
  }
  // The value of the option just read by Next().
  std::string TakeValue(const std::string& option) {
    if (has_pending_) {
      has_pending_ = false;
      return pending_value_;
    }
    if (i_ >= argc_) throw UsageError(command_ + ": option " + option + " needs a value");
    return argv_[i_++];
  }
  // Rejects "--flag=value" for options that take no value.
  void NoValue(const std::string& option) const {
    if (has_pending_) throw UsageError(command_ + ": option " + option + " takes no value");
  }

 private:
  int argc_;
  const char* const* argv_;
  int i_;                      // next argument to read
  std::string command_;        // subcommand, for messages
  std::string pending_value_;  // value given as --name=value
  bool has_pending_ = false;
  std::set<std::string> seen_; // options read so far
};

bool IsOption(const std::string& arg) { return arg.size() > 1 && arg[0] == '-'; }

[[noreturn]] void UnknownOption(const std::string& command, const std::string& option) {
  throw UsageError(command + ": unknown option " + option);
}

// Checks the positional count.
void ExpectPositionals(const std::string& command, const std::vector<std::string>& got,
                       size_t want, const std::string& names) {
  if (got.size() < want) throw UsageError(command + ": missing " + names);
  if (got.size() > want) throw UsageError(command + ": unexpected argument '" + got[want] + "'");
}

void CheckSet(const std::string& command, const std::string& value) {
  const size_t eq = value.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw UsageError(command + ": --set expects key.path=value, got '" + value + "'");
  }
}

RunArgs ParseRun(ArgCursor* c) {
  RunArgs a;
  std::vector<std::string> pos;
  while (!c->Done()) {
    const std::string arg = c->Next();
    if (!IsOption(arg)) {
      pos.push_back(arg);
    } else if (arg == "--out") {
      a.options.out_dir = c->TakeValue(arg);
    } else if (arg == "--force") {
      c->NoValue(arg);
      a.options.force = true;
    } else if (arg == "--set") {
      a.sets.push_back(c->TakeValue(arg));
      CheckSet("run", a.sets.back());
    } else if (arg == "--no-slam") {
      c->NoValue(arg);
      a.options.slam = false;
    } else if (arg == "--record") {
      c->NoValue(arg);
      a.options.record = true;
    } else if (arg == "--record-tum") {
      c->NoValue(arg);
      a.options.record_tum = true;
    } else if (arg == "--video") {
      c->NoValue(arg);
      a.options.video = true;
    } else if (arg == "--report") {
      c->NoValue(arg);
      a.options.report = true;
    } else if (arg == "--sequential") {
      c->NoValue(arg);
      a.options.sequential = true;
    } else {
      UnknownOption("run", arg);
    }
  }
  ExpectPositionals("run", pos, 1, "SCENARIO.yaml");
  a.scenario = pos[0];
  return a;
}

SlamArgs ParseSlam(ArgCursor* c) {
  SlamArgs a;
  std::vector<std::string> pos;
  while (!c->Done()) {
    const std::string arg = c->Next();
    if (!IsOption(arg)) {
      pos.push_back(arg);
    } else if (arg == "--format") {
      a.format = c->TakeValue(arg);
      if (a.format != "viqu" && a.format != "euroc" && a.format != "tum") {
        throw UsageError("slam: --format expects viqu, euroc or tum, got '" + a.format + "'");
      }
    } else if (arg == "--config") {
      a.config = c->TakeValue(arg);
    } else if (arg == "--out") {
      a.out_dir = c->TakeValue(arg);
    } else if (arg == "--force") {
      c->NoValue(arg);
      a.force = true;
    } else if (arg == "--camera") {
      a.camera = c->TakeValue(arg);
    } else if (arg == "--masks") {
      a.masks_dir = c->TakeValue(arg);
    } else if (arg == "--skip-bad-frames") {
      const std::optional<std::string> v = c->TakeOptionalNumber();
      a.skip_bad_frames = 1;
      if (v) {
        char* end = nullptr;
        errno = 0;
        const long n = std::strtol(v->c_str(), &end, 10);
        if (v->empty() || *end != '\0' || errno == ERANGE || n < 1 || n > 1'000'000) {
          throw UsageError("slam: --skip-bad-frames expects a whole number of frames from 1 to 1000000, got '" + *v + "'");
        }
        a.skip_bad_frames = static_cast<int>(n);
      }
    } else if (arg == "--set") {
      a.sets.push_back(c->TakeValue(arg));
      CheckSet("slam", a.sets.back());
    } else {
      UnknownOption("slam", arg);
    }
  }
  ExpectPositionals("slam", pos, 1, "DATASET_DIR");
  a.dataset_dir = pos[0];
  return a;
}

EvalArgs ParseEval(ArgCursor* c) {
  EvalArgs a;
  bool delta_frames_given = false;
  std::vector<std::string> pos;
  while (!c->Done()) {
    const std::string arg = c->Next();
    if (!IsOption(arg)) {
      pos.push_back(arg);
    } else if (arg == "--json") {
      c->NoValue(arg);
      a.json = true;
    } else if (arg == "--sim3") {
      c->NoValue(arg);
      a.sim3 = true;
    } else if (arg == "--delta") {
      const std::string v = c->TakeValue(arg);
      char* end = nullptr;
      errno = 0;
      const long long n = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || errno == ERANGE || n < 1 || n > kMaxDeltaFrames) {
        throw UsageError("eval: --delta expects a whole number of frames from 1 to " + std::to_string(kMaxDeltaFrames) +
                         ", got '" + v + "'");
      }
      a.delta_frames = static_cast<int>(n);
      delta_frames_given = true;
    } else if (arg == "--delta-m") {
      const std::string v = c->TakeValue(arg);
      const std::optional<double> x = FiniteNumber(v);
      if (!x || !(*x > 0)) throw UsageError("eval: --delta-m expects a positive number of metres, got '" + v + "'");
      a.delta_m = *x;
    } else {
      UnknownOption("eval", arg);
    }
  }
  if (delta_frames_given && a.delta_m > 0) throw UsageError("eval: --delta and --delta-m exclude each other");
  ExpectPositionals("eval", pos, 2, pos.empty() ? "EST.txt and GT.txt" : "GT.txt");
  a.estimate = pos[0];
  a.ground_truth = pos[1];
  return a;
}

SweepArgs ParseSweep(ArgCursor* c) {
  SweepArgs a;
  a.jobs = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::string> pos;
  while (!c->Done()) {
    const std::string arg = c->Next();
    if (!IsOption(arg)) {
      pos.push_back(arg);
    } else if (arg == "--jobs") {
      const std::string v = c->TakeValue(arg);
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n < 1 || n > 1024) {
        throw UsageError("sweep: --jobs expects a whole number from 1 to 1024, got '" + v + "'");
      }
      a.jobs = static_cast<int>(n);
    } else if (arg == "--out") {
      a.out_dir = c->TakeValue(arg);
    } else if (arg == "--resume") {
      c->NoValue(arg);
      a.resume = true;
    } else if (arg == "--emit") {
      a.emit = c->TakeValue(arg);
      if (a.emit != "slurm" && a.emit != "list") throw UsageError("sweep: --emit expects slurm or list, got '" + a.emit + "'");
    } else if (arg == "--collect") {
      a.collect_dir = c->TakeValue(arg);
    } else {
      UnknownOption("sweep", arg);
    }
  }
  if (!a.collect_dir.empty()) {
    if (!pos.empty() || !a.out_dir.empty() || a.resume || !a.emit.empty()) {
      throw UsageError("sweep: --collect DIR takes no sweep file and no other option");
    }
    return a;
  }
  ExpectPositionals("sweep", pos, 1, "SWEEP.yaml");
  a.sweep_file = pos[0];
  return a;
}

ReportArgs ParseReport(ArgCursor* c) {
  ReportArgs a;
  std::vector<std::string> pos;
  while (!c->Done()) {
    const std::string arg = c->Next();
    if (!IsOption(arg)) {
      pos.push_back(arg);
    } else if (arg == "--x" || arg == "--y" || arg == "--metric") {
      a.tool_args.push_back(arg);
      a.tool_args.push_back(c->TakeValue(arg));
    } else {
      UnknownOption("report", arg);
    }
  }
  ExpectPositionals("report", pos, 1, "DIR");
  a.dir = pos[0];
  return a;
}

ViewArgs ParseView(ArgCursor* c) {
  ViewArgs a;
  std::vector<std::string> pos;
  while (!c->Done()) {
    const std::string arg = c->Next();
    if (!IsOption(arg)) {
      pos.push_back(arg);
    } else if (arg == "--set") {
      a.sets.push_back(c->TakeValue(arg));
      CheckSet("view", a.sets.back());
    } else if (arg == "--out") {
      a.options.out_dir = c->TakeValue(arg);
    } else if (arg == "--force") {
      c->NoValue(arg);
      a.options.force = true;
    } else if (arg == "--no-slam") {
      c->NoValue(arg);
      a.options.slam = false;
    } else if (arg == "--speed") {
      const std::string v = c->TakeValue(arg);
      const std::optional<double> x = FiniteNumber(v);
      if (!x || !(*x >= 0)) {
        throw UsageError("view: --speed expects a number >= 0 (simulated seconds per second; 0: as fast as it runs), got '" + v + "'");
      }
      a.speed = *x;
    } else if (arg == "--paused") {
      c->NoValue(arg);
      a.paused = true;
    } else if (arg == "--exit-at-end") {
      c->NoValue(arg);
      a.exit_at_end = true;
    } else if (arg == "--screenshot") {
      a.screenshot = c->TakeValue(arg);
    } else {
      UnknownOption("view", arg);
    }
  }
  ExpectPositionals("view", pos, 1, "SCENARIO.yaml");
  a.scenario = pos[0];
  return a;
}

}  // namespace

CliArgs ParseCommandLine(int argc, const char* const argv[]) {
  CliArgs args;
  if (argc < 2) throw UsageError("missing command");
  const std::string command = argv[1];
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i == 1 && (arg == "--version" || arg == "version")) {
      args.command = Command::kVersion;
      return args;
    }
    if (arg == "-h" || arg == "--help") {
      args.command = Command::kHelp;
      const bool known = command == "run" || command == "slam" || command == "eval" ||
                         command == "sweep" || command == "report" || command == "view";
      args.help_topic = known ? command : "";
      return args;
    }
  }
  if (command == "help") {
    args.command = Command::kHelp;
    if (argc > 2) args.help_topic = argv[2];
    if (!args.help_topic.empty() && UsageText(args.help_topic).empty()) {
      throw UsageError("help: unknown command '" + args.help_topic + "'");
    }
    return args;
  }
  for (int i = 0; i < argc; ++i) {
    if (i > 0) args.command_line += ' ';
    const std::string arg = argv[i];
    const bool plain = !arg.empty() && arg.find_first_of(" \t\n'\"\\$`*?[]{}()<>|&;#~") == std::string::npos;
    if (plain) {
      args.command_line += arg;
    } else {
      args.command_line += '\'';
      for (char ch : arg) args.command_line += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
      args.command_line += '\'';
    }
  }
  ArgCursor cursor(argc, argv, 2, command);
  if (command == "run") {
    args.command = Command::kRun;
    args.run = ParseRun(&cursor);
  } else if (command == "slam") {
    args.command = Command::kSlam;
    args.slam = ParseSlam(&cursor);
  } else if (command == "eval") {
    args.command = Command::kEval;
    args.eval = ParseEval(&cursor);
  } else if (command == "sweep") {
    args.command = Command::kSweep;
    args.sweep = ParseSweep(&cursor);
  } else if (command == "report") {
    args.command = Command::kReport;
    args.report = ParseReport(&cursor);
  } else if (command == "view") {
    args.command = Command::kView;
    args.view = ParseView(&cursor);
  } else {
    throw UsageError("unknown command '" + command + "'");
  }
  return args;
}

std::string UsageText(const std::string& topic) {
  if (topic == "run") return std::string("usage: ") + kRunUsage;
  if (topic == "slam") return std::string("usage: ") + kSlamUsage;
  if (topic == "eval") return std::string("usage: ") + kEvalUsage;
  if (topic == "sweep") return std::string("usage: ") + kSweepUsage;
  if (topic == "report") return std::string("usage: ") + kReportUsage;
  if (topic == "view") return std::string("usage: ") + kViewUsage;
  if (!topic.empty()) return "";
  return std::string("usage: viqu COMMAND [ARGS]   (viqu COMMAND --help for details)\n\n") + kRunUsage +
         kSlamUsage + kEvalUsage + kSweepUsage + kReportUsage + kViewUsage +
         "viqu --version\n    the version and the git commit it was built from\n"
         "\nexit codes: 0 ok, 1 run failed (e.g. the robot fell), 2 bad input or usage (the message names the\n"
         "file, and line:column for YAML), 130 / 143 stopped by SIGINT / SIGTERM (the run folder is\n"
         "complete so far and marked run_incomplete.json)\n";
}

}  // namespace viqu::app

#pragma once
#include <string>
#include <vector>

#include "runner/run_options.h"

namespace viqu::app {

// `viqu run SCENARIO.yaml [--out DIR] [--set key.path=value ...] [--no-slam] [--record] [--video]`
struct RunArgs {
  std::string scenario;           // scenario YAML path
  std::vector<std::string> sets;  // "key.path=value" overrides, in command-line order
  runner::RunOptions options;           // out_dir empty when --out was not given
};

// `viqu slam DATASET_DIR [--format viqu|euroc|tum] [--config FILE] [--camera FILE] [--out DIR] [--force] [--masks DIR]
//  [--set key.path=value ...]`
struct SlamArgs {
  std::string dataset_dir;        // recorded run folder or public dataset
  std::string format = "viqu";    // viqu | euroc | tum
  std::string config;             // SLAM settings file; empty = slam/config/default.yaml
  std::string out_dir;            // empty when --out was not given
  bool force = false;             // --force: --out may replace a non-empty folder holding no run
  std::string camera;             // --camera: calibration file; empty = the dataset's own
  std::string masks_dir;          // instance masks (docs/MASKS.md); empty when --masks was not given
  int skip_bad_frames = 0;        // --skip-bad-frames [N]: up to N lone unreadable frames are skipped
                                  // (N 1 when not given), not exit 2; 0 = none
  std::vector<std::string> sets;  // "key.path=value" SLAM settings overrides, in command-line order
};

// `viqu eval EST.txt GT.txt [--json]`
struct EvalArgs {
  std::string estimate;           // TUM trajectory to evaluate
  std::string ground_truth;       // TUM reference trajectory
  bool json = false;              // print one JSON object instead of text
  bool sim3 = false;              // align with a similarity (scale too) instead of SE(3)
  int delta_frames = 1;           // RPE pair distance in associated frames (--delta N)
  double delta_m = 0;             // RPE pair distance in metres of path (--delta-m D); 0 = frames
};

// `viqu sweep SWEEP.yaml [--jobs N] [--out DIR] [--resume] [--emit slurm|list]`, `viqu sweep --collect DIR`
struct SweepArgs {
  std::string sweep_file;         // sweep YAML (apps/sweep_spec.h); empty with --collect
  int jobs = 1;                   // parallel processes (>= 1); the parser fills in the number of cores
  std::string out_dir;            // sweep folder; empty = sweeps/<sweep file name>
  bool resume = false;            // skip points whose run folder is complete
  std::string emit;               // "" (run), "slurm" or "list": write the manifest instead
  std::string collect_dir;        // --collect: build the tables of this sweep folder
};

// `viqu report DIR [--x KEY] [--y KEY] [--metric M]`
struct ReportArgs {
  std::string dir;                // run folder or sweep folder
  std::vector<std::string> tool_args;  // --x/--y/--metric, passed on to tools/report.py
};

// `viqu view SCENARIO.yaml [--out DIR] [--force] [--set key.path=value ...] [--no-slam] [--speed X] [--paused]
//  [--exit-at-end] [--screenshot FILE]`: the run of `viqu run` (same outputs) shown in a window.
struct ViewArgs {
  std::string scenario;           // scenario YAML path
  std::vector<std::string> sets;  // overrides, as for run
  runner::RunOptions options;     // out_dir empty when --out was not given (then runs/<name>-view)
  double speed = 1.0;             // simulated s per wall s; 0 = as fast as it goes
  bool paused = false;            // start paused
  bool exit_at_end = false;       // close the window when the run ends
  std::string screenshot;         // PNG of the window when the viewer ends; empty = none
};

enum class Command { kHelp, kVersion, kRun, kSlam, kEval, kSweep, kReport, kView };

// The parsed command line; only the member of `command` is filled in.
struct CliArgs {
  Command command = Command::kHelp;
  std::string help_topic;         // kHelp: "" for the overview, else a subcommand name
  std::string command_line;       // the whole command, quoted for a shell (recorded in run folders)
  RunArgs run;
  SlamArgs slam;
  EvalArgs eval;
  SweepArgs sweep;
  ReportArgs report;
  ViewArgs view;
};

// Parses argv (argv[0] is the program). Options take their value as the next argument or
// after '=' ("--out DIR", "--out=DIR"). `-h`/`--help` anywhere asks for help. Throws
// UsageError on anything malformed.
CliArgs ParseCommandLine(int argc, const char* const argv[]);

// Usage text: the overview for an empty topic, else that subcommand's.
std::string UsageText(const std::string& topic = "");

}  // namespace viqu::app

#pragma once
#include <string>

namespace viqu::runner {

// What `viqu run` was asked to produce, besides the scenario itself.
struct RunOptions {
  std::string out_dir;  // run folder (created if missing); the CLI fills in runs/<scenario name>
  bool force = false;   // --force: out_dir may replace a non-empty folder that holds no viqu run
  std::string command_line;  // the command that asked for the run (recorded in the completion marker)
  bool slam = true;     // run the SLAM estimator live (--no-slam turns it off)
  bool record = false;  // write the EuRoC-layout dataset under out_dir/dataset (--record)
  bool record_tum = false;  // write a TUM RGB-D dataset under out_dir/dataset_tum (--record-tum)
  bool video = false;   // write out_dir/video.mp4 (--video)
  bool sequential = false;  // --sequential: estimator on the simulation's thread (same outputs, slower)
  bool report = false;  // plots into out_dir/plots after the run (--report)
};

}  // namespace viqu::runner

#pragma once
// A sweep file (`viqu sweep SWEEP.yaml`): a grid of scenario keys over scenarios and seeds, read
// strictly (unknown keys, wrong types: InputError with FILE:LINE:COL), and its expansion into
// points, one `viqu run` each.
//
//   scenarios: [../scenarios/static_room.yaml]   # paths relative to the sweep file
//   seeds: [1, 2]                                # or a count: seeds: 3 means 1, 2, 3
//   grid:                                        # any key `viqu run --set` takes
//     slam.dynamic.th_d: [0.02, 0.05]
//     sensors.camera.noise_std: [1, 2, 4]
//   fixed: {duration_s: 10}                      # set on every point
//   metrics: [ate.rmse_m, tracking.lost_frames]  # dotted metrics.json keys to collect
//   best: {dynamic.recall: max}                  # per metric: min (default) or max is best
//   timeout_s: 600                               # a point running longer is stopped (0: never)
#include <string>
#include <vector>

namespace viqu::app {

struct SweepSpec {
  std::string source_file;                 // the sweep file
  std::vector<std::string> scenarios;      // absolute paths
  std::vector<std::string> scenario_names; // each scenario's `name` (filled by LoadSweepSpec)
  std::vector<uint64_t> seeds;
  // Grid keys in file order, each with its values as `--set` text (YAML flow form).
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;
  std::vector<std::pair<std::string, std::string>> fixed;  // key, value text
  std::vector<std::string> metrics;
  std::vector<bool> maximise;              // per metric: true when larger is better
  double timeout_s = 0;                    // 0 = no limit
};

// One run of the sweep.
struct SweepPoint {
  std::string id;                          // "p0000", ... in expansion order
  std::string scenario;                    // absolute path
  std::string scenario_name;               // the scenario's `name`
  uint64_t seed = 0;
  std::vector<std::string> values;         // one per grid key, as --set text
  std::vector<std::string> sets;           // every --set of the run: fixed, grid, seed
};

// Reads and checks a sweep file. Every point's `--set` list is tried on its scenario (the
// scenario loader), so that a key `viqu run` would reject is exit 2 before anything runs.
SweepSpec LoadSweepSpec(const std::string& path);

// The points: scenarios x grid (last key fastest) x seeds, in that order.
std::vector<SweepPoint> ExpandSweep(const SweepSpec& spec);

// The resolved sweep (absolute scenario paths) as YAML: LoadSweepSpec of it gives the same
// points. Stored as DIR/sweep.yaml for --collect and Slurm.
std::string SweepSpecToYaml(const SweepSpec& spec);

}  // namespace viqu::app

#pragma once
// The tables of a sweep, built from its points' run folders alone (so that a local sweep, a
// resumed one and `--collect` after a Slurm array give the same tables): results.csv, one row
// per point; summary.csv, per grid point over seeds; the best grid point per metric.
#include <string>
#include <vector>

#include "apps/sweep_spec.h"

namespace viqu::app {

// What is known of one point after the runs.
struct PointOutcome {
  std::string status;          // ok | failed | timeout | missing (no complete run folder)
  std::string exit_code;       // the run's exit code ("" when unknown)
  std::vector<std::string> metrics;  // per spec.metrics: the metrics.json value, "" when absent
  std::string wall_s;          // timing.wall_time_s of the run
};

// Reads a point's run folder: complete -> its marker's exit code and the metrics; otherwise
// status "missing" (the caller may know better: failed, timeout).
PointOutcome ReadPointOutcome(const SweepSpec& spec, const std::string& run_dir);

// Writes DIR/results.csv and DIR/summary.csv (atomically) and returns the lines naming the best
// grid point per metric (by mean over seeds; min or max as spec.maximise says). The summary's
// statistics and the best point use the points with status ok only; results.csv has every one.
std::vector<std::string> WriteSweepTables(const SweepSpec& spec, const std::vector<SweepPoint>& points,
                                          const std::vector<PointOutcome>& outcomes, const std::string& dir);

// A CSV field, quoted when it holds a comma, a quote or a newline.
std::string CsvField(const std::string& text);

}  // namespace viqu::app

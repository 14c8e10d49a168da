#pragma once
#include <string>

#include "apps/cli.h"

namespace viqu::app {

// `viqu sweep SWEEP.yaml [--jobs N] [--out DIR] [--resume] [--emit slurm|list]` and
// `viqu sweep --collect DIR`. Runs one `viqu_exe run` process per point (sweep_spec.h) into
// DIR/points/<id>/ (log DIR/logs/<id>.log), at most N at once; a point that fails, falls or
// times out is recorded and the sweep goes on. --resume skips points whose run folder is
// complete. --emit writes DIR/manifest.txt (one shell command per point) and, for slurm,
// DIR/sweep.sbatch (a job array, task i runs line i + 1) instead of running. Writes
// DIR/sweep.yaml (resolved), DIR/results.csv, DIR/summary.csv and prints the best grid point
// per metric. Exit code 0 when every point ran (whatever their own exit codes), 130/143 when
// stopped by a signal.
int RunSweepCommand(const SweepArgs& args, const std::string& viqu_exe);

}  // namespace viqu::app

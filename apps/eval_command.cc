#include "apps/eval_command.h"

#include <cstdio>

#include "common/json_writer.h"
#include "common/run_folder.h"
#include "slam/eval/trajectory_error.h"

namespace viqu::app {

int RunEval(const EvalArgs& args) {
  RequireNotInIncompleteRun(args.estimate);
  RequireNotInIncompleteRun(args.ground_truth);
  const eval::Trajectory est = eval::ReadTumTrajectory(args.estimate);
  const eval::Trajectory gt = eval::ReadTumTrajectory(args.ground_truth);
  const eval::AteResult ate = eval::ComputeAte(est, gt, args.sim3);
  const eval::ErrorStats rpe = eval::ComputeRpe(est, gt, args.delta_frames, args.delta_m);
  JsonWriter j;
  j.Set("ate.rmse_m", ate.ate.rmse);
  j.Set("ate.mean_m", ate.ate.mean);
  j.Set("ate.median_m", ate.ate.median);
  j.Set("ate.std_m", ate.ate.std);
  j.Set("ate.min_m", ate.ate.min);
  j.Set("ate.max_m", ate.ate.max);
  j.Set("ate.pairs", ate.pairs);
  j.Set("rpe.trans_rmse_m", rpe.rmse);
  if (args.sim3) j.Set("ate.scale", ate.alignment.scale);
  if (args.json) {
    std::printf("%s\n", j.ToString().c_str());
  } else {
    std::printf("ATE (%s aligned, %zu pairs): rmse %.6f m, mean %.6f, median %.6f, std %.6f, min %.6f, max %.6f\n"
                "RPE: translation rmse %.6f m over %zu pairs\n",
                args.sim3 ? "Sim(3)" : "SE(3)", ate.pairs, ate.ate.rmse, ate.ate.mean, ate.ate.median, ate.ate.std, ate.ate.min, ate.ate.max,
                rpe.rmse, rpe.count);
  }
  return 0;
}

}  // namespace viqu::app

#include "apps/eval_command.h"

#include <cstdio>

#include "common/json_writer.h"
#include "slam/eval/trajectory_error.h"

namespace viqu::app {

int RunEval(const EvalArgs& args) {
  const eval::Trajectory est = eval::ReadTumTrajectory(args.estimate);
  const eval::Trajectory gt = eval::ReadTumTrajectory(args.ground_truth);
  const eval::AteResult ate = eval::ComputeAte(est, gt);
  const eval::ErrorStats rpe = eval::ComputeRpe(est, gt);
  JsonWriter j;
  j.Set("ate.rmse_m", ate.ate.rmse);
  j.Set("ate.mean_m", ate.ate.mean);
  j.Set("ate.median_m", ate.ate.median);
  j.Set("ate.std_m", ate.ate.std);
  j.Set("ate.min_m", ate.ate.min);
  j.Set("ate.max_m", ate.ate.max);
  j.Set("ate.pairs", ate.pairs);
  j.Set("rpe.trans_rmse_m", rpe.rmse);
  if (args.json) {
    std::printf("%s\n", j.ToString().c_str());
  } else {
    std::printf("ATE (SE(3) aligned, %zu pairs): rmse %.6f m, mean %.6f, median %.6f, std %.6f, min %.6f, max %.6f\n"
                "RPE (1 frame): translation rmse %.6f m over %zu pairs\n",
                ate.pairs, ate.ate.rmse, ate.ate.mean, ate.ate.median, ate.ate.std, ate.ate.min, ate.ate.max,
                rpe.rmse, rpe.count);
  }
  return 0;
}

}  // namespace viqu::app

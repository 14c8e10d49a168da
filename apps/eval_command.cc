#include "apps/eval_command.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "common/errors.h"
#include "common/json_writer.h"
#include "common/run_folder.h"
#include "slam/eval/trajectory_error.h"

namespace viqu::app {
namespace {

// "N poses from T0 to T1 s" for messages.
std::string Span(const eval::Trajectory& t) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%zu poses from %.3f to %.3f s", t.size(), t.front().t_ns * 1e-9, t.back().t_ns * 1e-9);
  return buf;
}

}  // namespace

int RunEval(const EvalArgs& args) {
  RequireNotInIncompleteRun(args.estimate);
  RequireNotInIncompleteRun(args.ground_truth);
  const eval::Trajectory est = eval::ReadTumTrajectory(args.estimate);
  const eval::Trajectory gt = eval::ReadTumTrajectory(args.ground_truth);
  for (const auto* t : {&est, &gt}) {
    if (t->empty()) throw InputError((t == &est ? args.estimate : args.ground_truth) + ": holds no poses");
  }
  const size_t associated = eval::Associate(est, gt, 0.02).size();
  if (associated < 3) {
    throw InputError(args.estimate + " and " + args.ground_truth + ": " + std::to_string(associated) +
                     " poses associated within 0.02 s; the alignment needs at least 3 (" + Span(est) + " and " + Span(gt) + ")");
  }
  const eval::AteResult ate = eval::ComputeAte(est, gt, args.sim3);
  const eval::ErrorStats rpe = eval::ComputeRpe(est, gt, args.delta_frames, args.delta_m);
  if (rpe.count == 0) {
    throw InputError(args.estimate + ": no pose pair " +
                     (args.delta_m > 0 ? std::to_string(args.delta_m) + " m of path apart"
                                       : std::to_string(args.delta_frames) + " associated poses apart") +
                     " among the " + std::to_string(associated) + " associated poses; use a smaller --delta or --delta-m");
  }
  if (!std::isfinite(ate.ate.rmse) || !std::isfinite(rpe.rmse)) {
    throw InputError(args.estimate + " and " + args.ground_truth + ": the errors are not finite numbers");
  }
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

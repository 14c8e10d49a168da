// Local BA's residual and Jacobian evaluation: written out (slam/core/local_ba.h, what local BA
// uses) against Ceres' automatic differentiation of the same residual (what it used before).
// Stereo observations; arg 0 = analytic, 1 = autodiff.
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include "slam/core/local_ba.h"
#include "slam/core/reprojection_cost.h"

namespace viqu::slam {
namespace {

void BM_BaResidualAndJacobians(benchmark::State& state) {
  StereoCamera cam;
  cam.width = 640;
  cam.height = 480;
  cam.fx = cam.fy = 415.7;
  cam.cx = 319.5;
  cam.cy = 239.5;
  cam.bf = 415.7 * 0.04;
  std::unique_ptr<ceres::CostFunction> cost;
  if (state.range(0) == 0) {
    cost.reset(MakeBaReprojectionCost(cam, 300, 200, 250, 0.8));
  } else {
    cost.reset(new ceres::AutoDiffCostFunction<StereoReprojectionCost, 3, 6, 3>(
        new StereoReprojectionCost(cam, 300, 200, 250, 0.8)));
  }
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<std::array<double, 9>> inputs(1024);
  for (auto& in : inputs) in = {0.3 * U(rng), 0.3 * U(rng), 0.3 * U(rng), U(rng), U(rng), U(rng), U(rng), U(rng), 3 + U(rng)};
  double r[3], jp[18], jx[9];
  double* jac[2] = {jp, jx};
  size_t i = 0;
  for (auto _ : state) {
    const auto& in = inputs[i++ & 1023];
    const double* params[2] = {in.data(), in.data() + 6};
    cost->Evaluate(params, r, jac);
    benchmark::DoNotOptimize(jp[0]);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BaResidualAndJacobians)->ArgName("autodiff")->Arg(0)->Arg(1);

}  // namespace
}  // namespace viqu::slam

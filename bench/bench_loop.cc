// The whole closed loop: `viqu run scenarios/walking_people.yaml` (10 s of it) through the
// runner library, as the command line runs it, and its real-time factor (simulated seconds per
// wall second). Arguments: SLAM on (1) or off (0); --record (1) or not (0); the estimator stage
// beside the simulation (0) or inline, --sequential (1). Peak RSS is the process's so far
// (getrusage), so read it on the first benchmark only; the 10-minute memory study is
// tools/memory_growth.py.
#include <sys/resource.h>

#include <filesystem>

#include <benchmark/benchmark.h>

#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

void BM_WalkingPeopleLoop(benchmark::State& state) {
  const std::string path = std::string(VIQU_SOURCE_DIR) + "/scenarios/walking_people.yaml";
  const Scenario s = LoadScenario(path, {"duration_s=10"});
  runner::RunOptions opt;
  opt.out_dir = (std::filesystem::temp_directory_path() / "viqu_bench_loop").string();
  opt.force = true;
  opt.slam = state.range(0) != 0;
  opt.record = state.range(1) != 0;
  opt.sequential = state.range(2) != 0;
  double sim_s = 0;
  for (auto _ : state) {
    if (runner::RunScenario(s, opt) != 0) state.SkipWithError("the run failed");
    sim_s += s.duration_s;
  }
  state.counters["real_time_factor"] = benchmark::Counter(sim_s, benchmark::Counter::kIsRate);
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  state.counters["peak_rss_mb"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
  std::filesystem::remove_all(opt.out_dir);
}
BENCHMARK(BM_WalkingPeopleLoop)
    ->ArgNames({"slam", "record", "sequential"})
    ->Args({1, 0, 0})
    ->Args({1, 0, 1})
    ->Args({1, 1, 0})
    ->Args({0, 0, 0})
    ->Args({0, 1, 0})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace viqu

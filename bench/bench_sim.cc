// Physics throughput of the walking robot, and the whole-run real-time factor of a scenario.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "runner/robot_rig.h"
#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"

namespace viqu {
namespace {

Scenario RoomScenario() {
  Scenario s;
  s.name = "bench_room";
  s.world = std::string(VIQU_SOURCE_DIR) + "/models/worlds/room.xml";
  s.robot.model = std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.xml";
  s.robot.command.velocity = {{0.0, 0.12, 0.1}};
  return s;
}

// Physics steps (1 ms) per second, robot trotting in the room: control + mj_step.
void BM_PhysicsStep(benchmark::State& state) {
  runner::RobotRig rig(RoomScenario());
  for (auto _ : state) rig.Step(rig.TruePose2());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PhysicsStep)->Unit(benchmark::kMicrosecond);

// The whole `viqu run` of scenarios/walking_people.yaml (10 s of it), 640x480 stereo at 20 Hz
// with depth and segmentation; arg 1 = with --record. Reports the real-time factor.
void BM_WalkingPeopleRun(benchmark::State& state) {
  const std::string path = std::string(VIQU_SOURCE_DIR) + "/scenarios/walking_people.yaml";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("scenarios/walking_people.yaml missing");
    return;
  }
  const Scenario s = LoadScenario(path, {"duration_s=10"});
  runner::RunOptions opt;
  opt.out_dir = (std::filesystem::temp_directory_path() / "viqu_bench_run").string();
  opt.slam = false;
  opt.record = state.range(0) != 0;
  double sim_s = 0;
  for (auto _ : state) {
    runner::RunScenario(s, opt);
    sim_s += s.duration_s;
  }
  state.counters["real_time_factor"] = benchmark::Counter(sim_s, benchmark::Counter::kIsRate);
  std::filesystem::remove_all(opt.out_dir);
}
BENCHMARK(BM_WalkingPeopleRun)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace viqu

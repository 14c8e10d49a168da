// SLAM per-frame tracking and per-keyframe local BA on a rendered 10 s walk of static_room
// (200 stereo frames at 20 Hz, 640x480, sync mapping). Each iteration runs a fresh SlamSystem
// over the whole sequence; the counters give the per-frame and per-keyframe figures.
#include <algorithm>
#include <vector>

#include <benchmark/benchmark.h>

#include "runner/robot_rig.h"
#include "runner/run_metrics.h"
#include "scenario/scenario_loader.h"
#include "sim/camera_noise.h"
#include "sim/stereo_renderer.h"
#include "slam/core/slam_system.h"
#include "slam/settings/slam_settings.h"

namespace viqu {
namespace {

constexpr double kSeconds = 10;
constexpr int kStepsPerFrame = 50;  // 1 kHz physics, 20 Hz camera

const std::vector<StereoFrame>& Sequence() {
  static const std::vector<StereoFrame> frames = [] {
    const Scenario s = LoadScenario(std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml", {});
    runner::RobotRig rig(s);
    sim::RenderOptions ro;
    ro.width = s.sensors.camera.width;
    ro.height = s.sensors.camera.height;
    ro.depth = false;
    ro.segmentation = false;
    sim::StereoRenderer renderer(rig.world().model(), ro);
    std::mt19937_64 rng(s.seed);
    std::vector<StereoFrame> out;
    const int n = static_cast<int>(kSeconds * 1000 / kStepsPerFrame);
    for (int i = 0; i < n; ++i) {
      StereoFrame f;
      renderer.Render(rig.world().model(), rig.world().data(), &f);
      sim::AddPixelNoise(&f.left_rgb, s.sensors.camera.noise_std, &rng);
      sim::AddPixelNoise(&f.right_rgb, s.sensors.camera.noise_std, &rng);
      out.push_back(f);
      for (int k = 0; k < kStepsPerFrame; ++k) rig.Step(rig.TruePose2());
    }
    return out;
  }();
  return frames;
}

void BM_SlamSequence(benchmark::State& state) {
  const auto& frames = Sequence();
  const slam::SlamSettings settings = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath());
  slam::SlamStats stats;
  for (auto _ : state) {
    slam::SlamSystem system(settings);
    for (const StereoFrame& f : frames) benchmark::DoNotOptimize(system.Track(f));
    system.Finish();
    stats = system.Stats();
  }
  state.counters["frames"] = static_cast<double>(frames.size());
  state.counters["track_ms_median"] = runner::Median(stats.track_ms);
  state.counters["track_ms_p95"] = runner::Percentile(stats.track_ms, 0.95);
  state.counters["keyframes"] = stats.keyframes;
  state.counters["local_ba_ms_median"] = runner::Median(stats.local_ba_ms);
  state.counters["lost"] = stats.lost_frames;
}
BENCHMARK(BM_SlamSequence)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
}  // namespace viqu

// Cost of one stereo frame of the off-screen renderer (sim/stereo_renderer.h): RGB pair alone,
// with left depth and/or instance segmentation, and what shadows, reflections, extra lights,
// the skybox and multisampling add. The scene is an inline textured room seen from a rig 7 cm
// above the floor, like the robot's camera; images are 640x480.
//
//   build-render/bench/bench_render --benchmark_counters_tabular=true
//
// Times are wall-clock per stereo frame (Render call: scene update, GL passes, read-backs and
// conversions); llvmpipe renders on worker threads, so CPU time of the caller would mislead.
// The counter proc_cpu_ms is the CPU time of the whole process (all llvmpipe threads) per
// frame: the work a frame takes, which varies less than wall time on a busy machine.
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>

#include "sim/mujoco_handles.h"
#include "sim/scene_composer.h"
#include "sim/stereo_renderer.h"

namespace viqu::sim {
namespace {

// A 6 m x 6 m room with textured walls, a reflective-capable floor, furniture, a person and a
// ball; `extra_lights` more spot lights under the ceiling (all may cast shadows).
std::string RoomXml(int extra_lights) {
  std::ostringstream x;
  x << R"(<mujoco model="bench_room">
  <visual><global offwidth="640" offheight="480"/></visual>
  <asset>
    <texture name="sky" type="skybox" builtin="gradient" rgb1=".4 .6 .8" rgb2="0 0 0" width="256" height="256"/>
    <texture name="floor" type="2d" builtin="checker" rgb1=".25 .2 .15" rgb2=".7 .65 .55" width="512" height="512"
             mark="random" random="0.05" markrgb=".1 .1 .1"/>
    <material name="floor" texture="floor" texrepeat="12 12" reflectance="0.2"/>
    <texture name="wall" type="2d" builtin="checker" rgb1=".6 .3 .2" rgb2=".9 .85 .7" width="256" height="256"
             mark="random" random="0.08" markrgb="0 0 0"/>
    <material name="wall" texture="wall" texrepeat="8 3"/>
    <texture name="crate" type="cube" builtin="checker" rgb1=".6 .45 .2" rgb2=".4 .3 .1" width="64" height="64"
             mark="edge" markrgb="0 0 0"/>
    <material name="crate" texture="crate"/>
  </asset>
  <worldbody>
    <light name="ceiling" pos="0 0 2.8" dir="0 0 -1" castshadow="true" diffuse=".6 .6 .6"/>
)";
  for (int i = 0; i < extra_lights; ++i) {
    const double px = -2.0 + 4.0 * (i % 3) / 2.0, py = (i < 3) ? -1.5 : 1.5;
    x << "    <light pos=\"" << px << " " << py << " 2.7\" dir=\"0 0 -1\" diffuse=\".2 .2 .2\" castshadow=\"true\"/>\n";
  }
  x << R"(    <geom name="floor" type="plane" size="3 3 0.1" material="floor"/>
    <geom type="box" pos="3 0 1.5" size="0.05 3 1.5" material="wall"/>
    <geom type="box" pos="-3 0 1.5" size="0.05 3 1.5" material="wall"/>
    <geom type="box" pos="0 3 1.5" size="3 0.05 1.5" material="wall"/>
    <geom type="box" pos="0 -3 1.5" size="3 0.05 1.5" material="wall"/>
    <body name="furniture:table" pos="1.8 0.8 0">
      <geom type="box" pos="0 0 0.7" size="0.6 0.4 0.03" rgba=".5 .35 .2 1"/>
      <geom type="cylinder" pos="0.5 0.3 0.35" size="0.03 0.35" rgba=".3 .2 .1 1"/>
      <geom type="cylinder" pos="-0.5 0.3 0.35" size="0.03 0.35" rgba=".3 .2 .1 1"/>
      <geom type="cylinder" pos="0.5 -0.3 0.35" size="0.03 0.35" rgba=".3 .2 .1 1"/>
      <geom type="cylinder" pos="-0.5 -0.3 0.35" size="0.03 0.35" rgba=".3 .2 .1 1"/>
    </body>
    <body name="furniture:shelf" pos="2.7 -1.2 0">
      <geom type="box" pos="0 0 1" size="0.2 0.6 1" rgba=".45 .4 .35 1"/>
    </body>
    <body name="box:crate" mocap="true" pos="1.2 -0.4 0.15"><geom type="box" size="0.15 0.15 0.15" material="crate"/></body>
    <body name="box:small" mocap="true" pos="0.9 0.5 0.08"><geom type="box" size="0.08 0.08 0.08" material="crate"/></body>
    <body name="ball:red" mocap="true" pos="1.5 0.2 0.1"><geom type="sphere" size="0.1" rgba=".8 .1 .1 1"/></body>
    <body name="person:ann" mocap="true" pos="2.2 -0.3 1.1">
      <geom type="capsule" size="0.16 0.3" rgba=".2 .4 .7 1"/>
      <geom type="sphere" pos="0 0 0.55" size="0.11" rgba=".9 .7 .6 1"/>
    </body>
    <body name="person:ann/leg_l" mocap="true" pos="2.2 -0.2 0.4"><geom type="capsule" size="0.06 0.35" rgba=".2 .2 .3 1"/></body>
    <body name="person:ann/leg_r" mocap="true" pos="2.2 -0.4 0.4"><geom type="capsule" size="0.06 0.35" rgba=".2 .2 .3 1"/></body>
    <body name="rig" pos="0 0 0.07">
      <camera name="cam_left" pos="0 0.02 0" xyaxes="0 -1 0 0.2 0 1" fovy="70"/>
      <camera name="cam_right" pos="0 -0.02 0" xyaxes="0 -1 0 0.2 0 1" fovy="70"/>
    </body>
  </worldbody>
</mujoco>)";
  return x.str();
}

// CPU time of the whole process, all threads (s).
double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Renders frames of `m` with `opt` and reports ms per stereo frame.
void RunFrames(benchmark::State& state, const RenderOptions& opt, ModelPtr m) {
  DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  StereoRenderer renderer(m.get(), opt);
  StereoFrame frame;
  for (int i = 0; i < 3; ++i) renderer.Render(m.get(), d.get(), &frame);  // shader JIT, caches
  const double cpu_start_s = ProcessCpuSeconds();
  for (auto _ : state) {
    renderer.Render(m.get(), d.get(), &frame);
    benchmark::DoNotOptimize(frame.left_rgb.data);
  }
  state.counters["proc_cpu_ms"] =
      1e3 * (ProcessCpuSeconds() - cpu_start_s) / static_cast<double>(state.iterations());
  state.SetLabel(renderer.device_description());
  for (const std::string& w : TakeMujocoWarnings()) state.SkipWithError(("MuJoCo warning: " + w).c_str());
}

// The inline room with `extra_lights`.
void RunFrames(benchmark::State& state, const RenderOptions& opt, int extra_lights) {
  RunFrames(state, opt, LoadModelString(RoomXml(extra_lights), "bench room"));
}

RenderOptions Lean(bool depth, bool segmentation) {
  RenderOptions opt;
  opt.depth = depth;
  opt.segmentation = segmentation;
  return opt;
}

// Args: depth (0/1), segmentation (0/1).
void BM_StereoFrame(benchmark::State& state) {
  RunFrames(state, Lean(state.range(0) != 0, state.range(1) != 0), 0);
}
BENCHMARK(BM_StereoFrame)
    ->ArgNames({"depth", "seg"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(40);

// Everything below: the full frame (depth + segmentation) plus one feature.
void BM_Shadows(benchmark::State& state) {
  RenderOptions opt = Lean(true, true);
  opt.shadows = true;
  RunFrames(state, opt, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_Shadows)->ArgName("extra_lights")->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

void BM_Reflections(benchmark::State& state) {
  RenderOptions opt = Lean(true, true);
  opt.reflections = true;
  RunFrames(state, opt, 0);
}
BENCHMARK(BM_Reflections)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

// Extra lights without shadows: per-fragment lighting cost of the fixed-function pipeline.
void BM_ExtraLights(benchmark::State& state) { RunFrames(state, Lean(true, true), static_cast<int>(state.range(0))); }
BENCHMARK(BM_ExtraLights)->ArgName("extra_lights")->Arg(2)->Arg(6)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

void BM_Skybox(benchmark::State& state) {
  RenderOptions opt = Lean(true, true);
  opt.skybox = true;
  opt.haze = true;
  RunFrames(state, opt, 0);
}
BENCHMARK(BM_Skybox)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

// Args: MSAA samples of the off-screen buffer (MuJoCo's default is 4).
void BM_Multisamples(benchmark::State& state) {
  RenderOptions opt = Lean(true, true);
  opt.multisamples = static_cast<int>(state.range(0));
  RunFrames(state, opt, 0);
}
BENCHMARK(BM_Multisamples)->ArgName("samples")->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

// All the looks at once: what a "pretty" configuration costs.
void BM_AllEffects(benchmark::State& state) {
  RenderOptions opt = Lean(true, true);
  opt.shadows = opt.reflections = opt.skybox = opt.haze = true;
  opt.multisamples = 4;
  RunFrames(state, opt, 2);
}
BENCHMARK(BM_AllEffects)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);

// The project's own room world with the robot rat (models/worlds/room.xml + models/rat/rat.xml,
// composed as a scenario would), robot at its start pose.
void BM_ProjectRoom(benchmark::State& state) {
  Scenario s;
  s.name = "bench_render";
  s.world = std::string(VIQU_SOURCE_DIR) + "/models/worlds/room.xml";
  s.robot.model = std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.xml";
  if (!std::ifstream(s.world) || !std::ifstream(s.robot.model)) {
    state.SkipWithError("models/worlds/room.xml or models/rat/rat.xml missing");
    for (auto _ : state) {
    }
    return;
  }
  RenderOptions opt = Lean(state.range(0) != 0, state.range(1) != 0);
  opt.multisamples = static_cast<int>(state.range(2));
  RunFrames(state, opt, LoadModelString(ComposeSceneXml(s, SceneHeader{}, {}), "bench project room"));
}
BENCHMARK(BM_ProjectRoom)
    ->ArgNames({"depth", "seg", "samples"})
    ->Args({0, 0, 0})
    ->Args({1, 1, 0})
    ->Args({1, 1, 4})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);

}  // namespace
}  // namespace viqu::sim

// ORB extraction and stereo matching on a rendered 640x480 stereo pair of the room.
#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>

#include "runner/robot_rig.h"
#include "sim/stereo_renderer.h"
#include "slam/features/orb_extractor.h"
#include "slam/features/stereo_matcher.h"
#include "slam/settings/slam_settings.h"

namespace viqu {
namespace {

struct Pair {
  cv::Mat left, right;
  double fx = 0, baseline = 0;
};

const Pair& RoomPair() {
  static const Pair pair = [] {
    Scenario s;
    s.name = "bench_features";
    s.world = std::string(VIQU_SOURCE_DIR) + "/models/worlds/room.xml";
    s.robot.model = std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.xml";
    s.robot.start.yaw_deg = 30;
    runner::RobotRig rig(s);
    sim::RenderOptions ro;
    ro.depth = false;
    ro.segmentation = false;
    sim::StereoRenderer renderer(rig.world().model(), ro);
    StereoFrame f;
    renderer.Render(rig.world().model(), rig.world().data(), &f);
    Pair p;
    cv::cvtColor(f.left_rgb, p.left, cv::COLOR_RGB2GRAY);
    cv::cvtColor(f.right_rgb, p.right, cv::COLOR_RGB2GRAY);
    p.fx = f.intrinsics.fx;
    p.baseline = f.baseline_m;
    return p;
  }();
  return pair;
}

void BM_OrbExtract(benchmark::State& state) {
  const Pair& p = RoomPair();
  slam::OrbExtractor orb;
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  for (auto _ : state) orb.Extract(p.left, cv::Mat(), &kps, &desc);
  state.counters["features"] = static_cast<double>(kps.size());
}
BENCHMARK(BM_OrbExtract)->Unit(benchmark::kMillisecond);

// Stereo matching with the options of slam/config/default.yaml (arg 0: what runs) and with the
// sheared windows and equiangular sub-pixel on (arg 1: stereo.max_shear 0.6, shear_step 0.2).
void BM_StereoMatch(benchmark::State& state) {
  const Pair& p = RoomPair();
  slam::OrbExtractor orb;
  std::vector<cv::KeyPoint> kl, kr;
  cv::Mat dl, dr;
  orb.Extract(p.left, cv::Mat(), &kl, &dl);
  orb.Extract(p.right, cv::Mat(), &kr, &dr);
  slam::StereoMatcherOptions opt = slam::LoadSlamSettings(slam::DefaultSlamSettingsPath()).stereo;
  if (state.range(0) == 1) {
    opt.max_shear = 0.6;
    opt.shear_step = 0.2;
    opt.subpixel = "equiangular";
  }
  slam::StereoMatcher matcher(opt);
  for (auto _ : state) benchmark::DoNotOptimize(matcher.Match(p.left, p.right, kl, dl, kr, dr, p.fx, p.baseline));
}
BENCHMARK(BM_StereoMatch)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace viqu

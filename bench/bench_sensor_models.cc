// Micro-benchmarks of the sensor models in sim/: what they cost per reading or per image.
#include <array>
#include <random>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include "sim/camera_noise.h"
#include "sim/encoder_model.h"
#include "sim/imu_model.h"
#include "sim/segmentation_model.h"

namespace {

void BM_ImuMeasure(benchmark::State& state) {
  viqu::sim::ImuModel imu(viqu::ImuConfig{}, 1);
  int64_t t_ns = 0;
  for (auto _ : state) {
    t_ns += 5'000'000;
    benchmark::DoNotOptimize(imu.Measure(t_ns, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero()));
  }
}
BENCHMARK(BM_ImuMeasure);

void BM_EncoderMeasure(benchmark::State& state) {
  viqu::sim::EncoderModel enc(viqu::JointsConfig{}, 1);
  const std::array<double, viqu::kNumJoints> q{0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7, -0.8}, qd{};
  int64_t t_ns = 0;
  for (auto _ : state) {
    t_ns += 5'000'000;
    benchmark::DoNotOptimize(enc.Measure(t_ns, q, qd, {}));
  }
}
BENCHMARK(BM_EncoderMeasure);

// One 640x480 RGB image (the camera does two per frame).
void BM_AddPixelNoise640x480(benchmark::State& state) {
  cv::Mat img(480, 640, CV_8UC3, cv::Scalar::all(128));
  std::mt19937_64 rng(1);
  for (auto _ : state) viqu::sim::AddPixelNoise(&img, 2.0, &rng);
}
BENCHMARK(BM_AddPixelNoise640x480)->Unit(benchmark::kMillisecond);

// A 640x480 frame with six detectable instances and the robot, depth present, dilation 2.
void BM_Segmentation640x480(benchmark::State& state) {
  viqu::StereoFrame base;
  base.left_instance_id = cv::Mat::zeros(480, 640, CV_16UC1);
  base.left_depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(4.0f));
  for (uint16_t id = 1; id <= 6; ++id) {
    const cv::Rect r(40 + 90 * (id - 1), 100 + 20 * id, 60, 150);
    base.left_instance_id(r).setTo(id);
    base.left_depth_m(r).setTo(0.5f + 0.3f * id);
    base.instances.push_back({id, viqu::Category::kPerson, "person:p" + std::to_string(id)});
  }
  base.left_instance_id(cv::Rect(0, 430, 640, 50)).setTo(7);
  base.instances.push_back({7, viqu::Category::kRobot, "robot"});
  viqu::SegmentationConfig cfg;
  viqu::sim::SegmentationModel model(cfg, 1);
  for (auto _ : state) {
    viqu::StereoFrame f = base;
    f.left_instance_id = base.left_instance_id.clone();
    model.Apply(&f);
    benchmark::DoNotOptimize(f.left_instance_id.data);
  }
}
BENCHMARK(BM_Segmentation640x480)->Unit(benchmark::kMillisecond);

}  // namespace

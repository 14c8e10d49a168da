// What a recording costs per image: PNG encoding of a noisy 640x480 camera image, ours
// (sim/png_writer) against OpenCV's encoder with the settings the recorders used before.
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/camera_noise.h"
#include "sim/png_writer.h"

namespace {

// A textured view: tiles of varying shade with edges, and the camera's pixel noise (std 2).
cv::Mat CameraLikeImage() {
  cv::Mat img(480, 640, CV_8UC3);
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const int tile = ((x / 40) * 7 + (y / 30) * 13) % 11;
      img.at<cv::Vec3b>(y, x) = cv::Vec3b(60 + 15 * tile, 70 + 12 * tile + y / 8, 80 + 10 * tile + x / 10);
    }
  }
  std::mt19937_64 rng(3);
  viqu::sim::AddPixelNoise(&img, 2.0, &rng);
  return img;
}

void BM_EncodePngCamera(benchmark::State& state) {
  const cv::Mat img = CameraLikeImage();
  viqu::sim::PngEncoder encoder;  // one per writer thread, as the recorders' queue keeps it
  size_t bytes = 0;
  for (auto _ : state) bytes = encoder.Encode(img, viqu::sim::PngContent::kPhoto).size();
  state.counters["KB"] = bytes / 1024.0;
}
BENCHMARK(BM_EncodePngCamera)->Unit(benchmark::kMillisecond);

void BM_OpenCvPngHuffmanOnly(benchmark::State& state) {
  const cv::Mat img = CameraLikeImage();
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY,
                                   cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY};
  std::vector<uchar> buf;
  for (auto _ : state) cv::imencode(".png", img, buf, params);
  state.counters["KB"] = buf.size() / 1024.0;
}
BENCHMARK(BM_OpenCvPngHuffmanOnly)->Unit(benchmark::kMillisecond);

}  // namespace

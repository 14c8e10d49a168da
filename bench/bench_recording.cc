// What a recording costs per image: PNG encoding of a noisy 640x480 camera image, a depth image
// and a label image, ours (sim/png_writer) against OpenCV's encoder with the settings the
// recorders used before (Huffman-only for camera images, zlib level 1 for the others).
#include <cmath>
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

// A camera 0.1 m above a floor, rolled 3 degrees (as a trotting robot's camera is, so that the
// floor's depth changes along each row), 1.5 m from a wall seen at 30 degrees, a box on the
// floor: depth along the optical axis (K of the 640x480 camera, fy 343 px) in steps of 1/5000 m,
// as the recorders write it. Real rendered depth codes to about 126 KB in 2.7 ms (walking_people).
cv::Mat RoomLikeDepth() {
  const double f = 343, cx = 319.5, cy = 239.5, height = 0.1, roll = 3 * M_PI / 180;
  cv::Mat steps(480, 640, CV_16U);
  for (int y = 0; y < steps.rows; ++y) {
    for (int x = 0; x < steps.cols; ++x) {
      const double rx = (x - cx) / f, ry = (y - cy) / f;  // ray (rx, ry, 1), y down
      // Wall: points with z = 1.5 + tan(30 deg) x.
      double z = 1.5 / (1 - std::tan(30 * M_PI / 180) * rx);
      const double down = ry * std::cos(roll) + rx * std::sin(roll);  // the ray's downward part
      if (down > 0) z = std::min(z, height / down);                              // floor
      if (x > 380 && x < 470 && y > 260 && y < 330) z = std::min(z, 0.8 + 0.0004 * x);  // box face
      steps.at<uint16_t>(y, x) = static_cast<uint16_t>(std::lround(std::min(z, 13.0) * 5000));
    }
  }
  return steps;
}

// Instance ids: background 0, two standing people and a box, each a filled shape.
cv::Mat LabelLikeImage() {
  cv::Mat labels(480, 640, CV_16U, cv::Scalar(0));
  cv::ellipse(labels, cv::Point(200, 300), cv::Size(40, 150), 0, 0, 360, cv::Scalar(3), cv::FILLED);
  cv::ellipse(labels, cv::Point(330, 260), cv::Size(25, 100), 0, 0, 360, cv::Scalar(4), cv::FILLED);
  cv::rectangle(labels, cv::Rect(381, 261, 89, 69), cv::Scalar(9), cv::FILLED);
  cv::rectangle(labels, cv::Rect(0, 400, 640, 80), cv::Scalar(1), cv::FILLED);  // the floor's id
  return labels;
}

void EncodeFlat(benchmark::State& state, const cv::Mat& img) {
  viqu::sim::PngEncoder encoder;
  size_t bytes = 0;
  for (auto _ : state) bytes = encoder.Encode(img, viqu::sim::PngContent::kFlat).size();
  state.counters["KB"] = bytes / 1024.0;
}
void OpenCvLevel1(benchmark::State& state, const cv::Mat& img) {
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  std::vector<uchar> buf;
  for (auto _ : state) cv::imencode(".png", img, buf, params);
  state.counters["KB"] = buf.size() / 1024.0;
}
void BM_EncodePngDepth(benchmark::State& state) { EncodeFlat(state, RoomLikeDepth()); }
void BM_OpenCvPngDepthLevel1(benchmark::State& state) { OpenCvLevel1(state, RoomLikeDepth()); }
void BM_EncodePngLabels(benchmark::State& state) { EncodeFlat(state, LabelLikeImage()); }
void BM_OpenCvPngLabelsLevel1(benchmark::State& state) { OpenCvLevel1(state, LabelLikeImage()); }
BENCHMARK(BM_EncodePngDepth)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvPngDepthLevel1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EncodePngLabels)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvPngLabelsLevel1)->Unit(benchmark::kMillisecond);

}  // namespace

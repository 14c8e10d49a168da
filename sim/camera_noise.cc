#include "sim/camera_noise.h"

#include <cmath>
#include <sstream>

#include <opencv2/core.hpp>

#include "common/errors.h"

namespace viqu::sim {

namespace {

void CheckEightBit(const cv::Mat& rgb) {
  if (rgb.depth() != CV_8U) {
    std::ostringstream msg;
    msg << "AddPixelNoise: expected an 8-bit image, got OpenCV type " << rgb.type();
    throw viqu::InputError(msg.str());
  }
}

void CheckStd(double noise_std) {
  if (!(noise_std >= 0.0) || !std::isfinite(noise_std)) {
    std::ostringstream msg;
    msg << "AddPixelNoise: noise_std must be finite and >= 0, got " << noise_std;
    throw viqu::InputError(msg.str());
  }
}

}  // namespace

PixelNoiseDraw DrawPixelNoise(double noise_std, std::mt19937_64* rng) {
  if (rng == nullptr) throw viqu::InputError("AddPixelNoise: null generator");
  CheckStd(noise_std);
  PixelNoiseDraw draw;
  if (noise_std == 0.0) return draw;
  draw.noise_std = noise_std;
  // One draw from our generator seeds OpenCV's; cv::RNG(0) would silently become a fixed
  // default state, so map 0 to another value.
  draw.state = (*rng)();
  if (draw.state == 0) draw.state = 0x9E3779B97F4A7C15ull;
  return draw;
}

void ApplyPixelNoise(const PixelNoiseDraw& draw, cv::Mat* rgb) {
  if (rgb == nullptr) throw viqu::InputError("AddPixelNoise: null image");
  if (rgb->empty() || draw.noise_std == 0.0) return;
  CheckEightBit(*rgb);
  cv::RNG cv_rng(draw.state);
  // int16 noise: rounded to whole grey levels by fill(); cv::add saturates the sum to [0, 255].
  cv::Mat noise(rgb->size(), CV_MAKETYPE(CV_16S, rgb->channels()));
  cv_rng.fill(noise, cv::RNG::NORMAL, 0.0, draw.noise_std);
  cv::add(*rgb, noise, *rgb, cv::noArray(), CV_8U);
}

void AddPixelNoise(cv::Mat* rgb, double noise_std, std::mt19937_64* rng) {
  if (rgb == nullptr || rng == nullptr) {
    throw viqu::InputError("AddPixelNoise: null image or generator");
  }
  CheckStd(noise_std);
  if (rgb->empty() || noise_std == 0.0) return;
  CheckEightBit(*rgb);  // before the draw: a rejected image leaves *rng as it was
  ApplyPixelNoise(DrawPixelNoise(noise_std, rng), rgb);
}

}  // namespace viqu::sim

#pragma once
// Pixel noise of a camera image. Pure C++/OpenCV on plain inputs (no MuJoCo).
#include <cstdint>
#include <random>

#include <opencv2/core/mat.hpp>

namespace viqu::sim {

// Adds independent Gaussian noise N(0, noise_std^2) (grey levels) to every channel of every
// pixel of an 8-bit image (CV_8UC1/3/4), rounding the noise to whole grey levels and saturating
// the sum to [0, 255]. Because the output is digital, the realised noise std on a mid-grey image
// is sqrt(noise_std^2 + 1/12) (rounding), 2.02 for noise_std = 2.
//
// Determinism: the noise comes from a cv::RNG (OpenCV's fast vectorised generator, about 3 ms
// per 640x480 RGB image) seeded with one 64-bit draw from *rng per call, never from cv::theRNG;
// so the result depends only on the state of *rng, which advances by exactly one draw per call
// with noise_std > 0 (none when noise_std == 0 or the image is empty).
// Throws viqu::InputError for a null pointer, a non-8-bit image, or a negative / non-finite
// noise_std.
void AddPixelNoise(cv::Mat* rgb, double noise_std, std::mt19937_64* rng);

// AddPixelNoise in two steps, so that the noise can be drawn where the generator lives (the
// simulation thread, in the order of its other draws) and added elsewhere (the estimator's
// thread): for a non-empty image, ApplyPixelNoise(DrawPixelNoise(std, rng), img) gives the bytes
// AddPixelNoise(img, std, rng) gives and leaves *rng in the same state. DrawPixelNoise takes its
// one draw whenever noise_std > 0 and throws as AddPixelNoise does for a bad noise_std or a null
// generator; ApplyPixelNoise throws for a null or non-8-bit image (an empty one is left as it is).
struct PixelNoiseDraw {
  double noise_std = 0;  // grey levels; 0: no noise
  uint64_t state = 0;    // the seed of the image's noise
};
PixelNoiseDraw DrawPixelNoise(double noise_std, std::mt19937_64* rng);
void ApplyPixelNoise(const PixelNoiseDraw& draw, cv::Mat* rgb);

}  // namespace viqu::sim

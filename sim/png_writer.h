#pragma once
// Lossless PNG files for the recordings, written with zlib directly. OpenCV's encoder (libpng)
// tries every row filter on every row when given a compression level, which cost about as much
// as the compression itself on our noisy rendered images. Every row here gets the Sub filter (the
// difference to the pixel on the left); the coding suits the content (see PngContent). Any PNG
// reader reads the files.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace viqu::sim {

enum class PngContent {
  kPhoto,  // camera images: every byte a literal, Huffman-coded per block (sim/huffman_deflate.h;
           // sensor noise leaves few repeated strings to find)
  kFlat,   // label and depth images: literals and repeats at the byte, pixel and row before
           // (sim/huffman_deflate.h RepeatZlib; flat areas and smooth surfaces repeat there)
};

// Encodes images one after another with buffers it keeps: an encoder that stays (one per writer
// thread) allocates, and takes page faults, for its first images only. On this virtual machine a
// fresh 640x480 image's buffers cost more in page faults than its coding.
class PngEncoder {
 public:
  // Encodes `image` as PNG; the bytes are valid until the next call. Accepted: CV_8UC1 (grey),
  // CV_8UC3 whose bytes are in RGB order (as our renderer's; not OpenCV's BGR) and CV_16UC1
  // (grey, 16 bit). Throws viqu::RunError for any other type or an empty image.
  const std::string& Encode(const cv::Mat& image, PngContent content);

 private:
  std::vector<uint8_t> raw_;         // filtered scanlines
  std::vector<uint8_t> row_;         // one row of 16-bit samples in PNG's byte order
  std::vector<uint8_t> compressed_;  // the zlib stream
  std::string png_;                  // the file's bytes
};

// PngEncoder::Encode with an encoder of its own (tests, one-off images).
std::string EncodePng(const cv::Mat& image, PngContent content);

// Encodes with `encoder`, then writes the bytes to `path`. Returns an empty string on success,
// else a message naming the path.
std::string WritePng(const std::string& path, const cv::Mat& image, PngContent content, PngEncoder* encoder);

}  // namespace viqu::sim

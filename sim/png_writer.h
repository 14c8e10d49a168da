#pragma once
// Lossless PNG files for the recordings, written with zlib directly. OpenCV's encoder (libpng)
// tries every row filter on every row when given a compression level, which cost about as much
// as the compression itself on our noisy rendered images (15 ms a 640x480 RGB image against 8 ms
// here, same size). Every row here gets the Sub filter (the difference to the pixel on the left);
// the deflate strategy suits the content (see PngContent). Any PNG reader reads the files.
#include <string>

#include <opencv2/core/mat.hpp>

namespace viqu::sim {

enum class PngContent {
  kPhoto,  // camera images: Huffman coding only (sensor noise leaves few repeated strings)
  kFlat,   // label and depth images: deflate's string matching at its fastest level (smooth
           // surfaces give runs of equal differences)
};

// Encodes `image` as PNG. Accepted: CV_8UC1 (grey), CV_8UC3 whose bytes are in RGB order (as our
// renderer's; not OpenCV's BGR) and CV_16UC1 (grey, 16 bit). Throws viqu::RunError for any other
// type or an empty image.
std::string EncodePng(const cv::Mat& image, PngContent content);

// EncodePng, then writes the bytes to `path`. Returns an empty string on success, else a message
// naming the path.
std::string WritePng(const std::string& path, const cv::Mat& image, PngContent content);

}  // namespace viqu::sim

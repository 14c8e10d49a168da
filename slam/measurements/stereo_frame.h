#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace viqu {

// Semantic category of a segmented instance.
enum class Category : uint8_t { kBackground = 0, kPerson = 1, kBox = 2, kBall = 3, kFurniture = 4, kRobot = 5 };
inline const char* CategoryName(Category c) {
  switch (c) {
    case Category::kBackground: return "background";
    case Category::kPerson: return "person";
    case Category::kBox: return "box";
    case Category::kBall: return "ball";
    case Category::kFurniture: return "furniture";
    case Category::kRobot: return "robot";
  }
  return "unknown";
}

// Pinhole intrinsics of a rectified camera (pixels). Pixel centres are at integer coordinates.
struct PinholeIntrinsics {
  int width = 0, height = 0;  // (px)
  double fx = 0, fy = 0;      // focal lengths (px)
  double cx = 0, cy = 0;      // principal point (px)
};

// One instance in the segmentation image.
struct SegmentInstance {
  uint16_t id = 0;              // value in StereoFrame::instance_id (0 = static background)
  Category category = Category::kBackground;
  std::string name;             // obstacle name from the scenario, or the MuJoCo body name
};

// One rectified stereo frame. Images follow OpenCV conventions: row 0 is the top row.
struct StereoFrame {
  int64_t t_ns = 0;              // simulated time of exposure (ns)
  cv::Mat left_rgb;              // CV_8UC3, RGB order
  cv::Mat right_rgb;             // CV_8UC3, RGB order
  cv::Mat left_depth_m;          // CV_32F metric depth along the optical axis (m); empty if not rendered
  cv::Mat left_instance_id;      // CV_16U instance ids (0 = background); empty if not rendered
  std::vector<SegmentInstance> instances;  // description of every id present in left_instance_id
  PinholeIntrinsics intrinsics;  // same for both cameras
  double baseline_m = 0;         // right camera sits at +baseline along the left camera's x axis (m)
};

}  // namespace viqu

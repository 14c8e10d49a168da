#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/errors.h"
#include "sim/image_write_queue.h"

namespace viqu::sim {
namespace {

namespace fs = std::filesystem;

TEST(ImageWriteQueue, WritesEveryImageLosslesslyBeforeDrainReturns) {
  const fs::path dir = fs::temp_directory_path() / "viqu_image_queue";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ImageWriteQueue q(2);  // smaller than the number of images: Push must block and go on
  std::vector<cv::Mat> images;
  for (int i = 0; i < 10; ++i) {
    cv::Mat img(48, 64, CV_16UC1);
    cv::randu(img, 0, 65535);
    images.push_back(img);
    q.Push((dir / (std::to_string(i) + ".png")).string(), img.clone(), PngContent::kFlat);
  }
  q.Drain();
  for (int i = 0; i < 10; ++i) {
    const cv::Mat back = cv::imread((dir / (std::to_string(i) + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(back.type(), CV_16UC1);
    EXPECT_EQ(cv::norm(back, images[i], cv::NORM_INF), 0.0) << i;
  }
  fs::remove_all(dir);
}

TEST(ImageWriteQueue, ReportsAFailedWriteWithItsPath) {
  ImageWriteQueue q;
  q.Push("/nonexistent-folder/x.png", cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)), PngContent::kPhoto);
  try {
    q.Drain();
    FAIL() << "Drain did not throw";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x.png"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace viqu::sim

// The overlay video (runner/overlay_video.h): feature colours by fate, tinted masks with labels,
// the status corner; and a written video that reads back with every frame.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "runner/overlay_video.h"

namespace viqu::runner {
namespace {

namespace fs = std::filesystem;

StereoFrame GreyFrame() {
  StereoFrame f;
  f.t_ns = 3'200'000'000;
  f.left_rgb = cv::Mat(240, 320, CV_8UC3, cv::Scalar(128, 128, 128));
  f.left_instance_id = cv::Mat(240, 320, CV_16U, cv::Scalar(0));
  f.left_instance_id(cv::Rect(200, 100, 60, 100)).setTo(7);
  f.instances = {{7, Category::kPerson, "alice"}};
  return f;
}

slam::TrackResult Track() {
  slam::TrackResult r;
  r.status = slam::TrackStatus::kTracking;
  r.inliers = 412;
  r.marks = {{50, 150, slam::FeatureFate::kTracked}, {80, 150, slam::FeatureFate::kNew},
             {230, 150, slam::FeatureFate::kDropped}, {110, 150, slam::FeatureFate::kUnmatched}};
  slam::ObjectReport alice;
  alice.id = 7;
  alice.name = "alice";
  alice.dynamic = true;
  r.objects = {alice};
  return r;
}

TEST(OverlayVideo, FeaturesMasksAndStatusAreDrawn) {
  const StereoFrame f = GreyFrame();
  const slam::TrackResult r = Track();
  const cv::Mat img = OverlayVideo::Draw(f, &r, 0.0031);
  cv::imwrite((fs::temp_directory_path() / "viqu_overlay.png").string(), img);
  ASSERT_EQ(img.size(), f.left_rgb.size());
  // Feature dots in their fate's colour (BGR).
  EXPECT_EQ(img.at<cv::Vec3b>(150, 50), cv::Vec3b(60, 200, 60));   // tracked
  EXPECT_EQ(img.at<cv::Vec3b>(150, 80), cv::Vec3b(230, 200, 0));   // new
  EXPECT_EQ(img.at<cv::Vec3b>(150, 230), cv::Vec3b(40, 40, 230));  // dropped
  EXPECT_EQ(img.at<cv::Vec3b>(150, 110), cv::Vec3b(0, 210, 230));  // unmatched
  // The mask is tinted (inside changed, outside untouched) and a dynamic object is framed red.
  EXPECT_NE(img.at<cv::Vec3b>(180, 240), cv::Vec3b(128, 128, 128));
  EXPECT_EQ(img.at<cv::Vec3b>(180, 150), cv::Vec3b(128, 128, 128));
  EXPECT_EQ(img.at<cv::Vec3b>(150, 200), cv::Vec3b(40, 40, 230));
  // The status box in the top-left corner: black background with white text.
  const cv::Mat corner = img(cv::Rect(0, 0, 200, 10));
  EXPECT_GT(cv::countNonZero(corner.reshape(1) == 0), 1000);
  EXPECT_GT(cv::countNonZero(corner.reshape(1) > 200), 50);
  // Without SLAM: the plain image with the time only, no dots.
  const cv::Mat plain = OverlayVideo::Draw(f, nullptr, -1);
  EXPECT_NE(plain.at<cv::Vec3b>(150, 50), cv::Vec3b(60, 200, 60));
}

TEST(OverlayVideo, WritesAVideoThatReadsBack) {
  const fs::path path = fs::temp_directory_path() / "viqu_overlay_test.mp4";
  fs::remove(path);
  {
    OverlayVideo v(path.string(), 20, 320, 240);
    const slam::TrackResult r = Track();
    StereoFrame f = GreyFrame();
    for (int i = 0; i < 10; ++i) {
      f.t_ns += 50'000'000;
      v.Add(f, &r, 0.001 * i);
    }
    EXPECT_FALSE(fs::exists(path));  // nothing under the final name before Finish
    v.Finish();
  }
  cv::VideoCapture cap(path.string());
  ASSERT_TRUE(cap.isOpened());
  int frames = 0;
  cv::Mat m;
  while (cap.read(m)) {
    EXPECT_EQ(m.size(), cv::Size(320, 240));
    ++frames;
  }
  EXPECT_EQ(frames, 10);
}

}  // namespace
}  // namespace viqu::runner

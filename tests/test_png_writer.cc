// The recordings' PNG encoder, read back by OpenCV's decoder (libpng): an independent reader.
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"
#include "sim/png_writer.h"

namespace viqu::sim {
namespace {

cv::Mat Decode(const std::string& bytes) {
  const cv::Mat buf(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
  return cv::imdecode(buf, cv::IMREAD_UNCHANGED);
}

double MaxDiff(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

TEST(PngWriter, GreyImagesReadBackExactly) {
  cv::Mat grey(37, 53, CV_8UC1);  // odd sizes: no row or pixel count is a multiple of anything
  cv::randu(grey, 0, 256);
  for (PngContent c : {PngContent::kPhoto, PngContent::kFlat}) {
    const cv::Mat back = Decode(EncodePng(grey, c));
    ASSERT_EQ(back.type(), CV_8UC1);
    EXPECT_EQ(MaxDiff(back, grey), 0.0);
  }
}

TEST(PngWriter, ColourImagesAreStoredInRgbOrder) {
  cv::Mat rgb(29, 41, CV_8UC3);
  cv::randu(rgb, 0, 256);
  rgb.at<cv::Vec3b>(0, 0) = cv::Vec3b(250, 10, 0);  // red, in RGB order
  const cv::Mat back = Decode(EncodePng(rgb, PngContent::kPhoto));  // OpenCV decodes to BGR
  ASSERT_EQ(back.type(), CV_8UC3);
  EXPECT_EQ(back.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 10, 250));
  cv::Mat back_rgb;
  cv::cvtColor(back, back_rgb, cv::COLOR_BGR2RGB);
  EXPECT_EQ(MaxDiff(back_rgb, rgb), 0.0);
}

TEST(PngWriter, SixteenBitImagesKeepBothBytes) {
  cv::Mat depth(31, 47, CV_16UC1);
  cv::randu(depth, 0, 65536);
  depth.at<uint16_t>(3, 4) = 0x0102;  // the byte order shows
  depth.at<uint16_t>(3, 5) = 0xff00;
  for (PngContent c : {PngContent::kPhoto, PngContent::kFlat}) {
    const cv::Mat back = Decode(EncodePng(depth, c));
    ASSERT_EQ(back.type(), CV_16UC1);
    EXPECT_EQ(back.at<uint16_t>(3, 4), 0x0102);
    EXPECT_EQ(MaxDiff(back, depth), 0.0);
  }
}

TEST(PngWriter, ViewsIntoLargerImagesAreEncodedByTheirOwnRows) {
  cv::Mat big(40, 60, CV_8UC3);
  cv::randu(big, 0, 256);
  const cv::Mat roi = big(cv::Rect(7, 5, 30, 20));  // rows with a stride longer than the view
  cv::Mat back_rgb;
  cv::cvtColor(Decode(EncodePng(roi, PngContent::kPhoto)), back_rgb, cv::COLOR_BGR2RGB);
  EXPECT_EQ(MaxDiff(back_rgb, roi), 0.0);
}

TEST(PngWriter, FlatContentCompressesLabelImages) {
  cv::Mat labels(480, 640, CV_16UC1, cv::Scalar(0));
  cv::rectangle(labels, cv::Rect(100, 80, 200, 300), cv::Scalar(7), cv::FILLED);
  const std::string png = EncodePng(labels, PngContent::kFlat);
  EXPECT_EQ(MaxDiff(Decode(png), labels), 0.0);
  EXPECT_LT(png.size(), labels.total() * 2 / 50) << "string matching should shrink a label image 50-fold";
}

TEST(PngWriter, OneEncoderKeepsNothingOfTheImageBefore) {
  // The encoder reuses its buffers: a large colour image, then smaller ones of other types.
  PngEncoder encoder;
  cv::Mat big(120, 160, CV_8UC3), grey(17, 23, CV_8UC1), depth(31, 11, CV_16UC1);
  cv::randu(big, 0, 256);
  cv::randu(grey, 0, 256);
  cv::randu(depth, 0, 65536);
  cv::Mat back;
  cv::cvtColor(Decode(encoder.Encode(big, PngContent::kPhoto)), back, cv::COLOR_BGR2RGB);
  EXPECT_EQ(MaxDiff(back, big), 0.0);
  EXPECT_EQ(MaxDiff(Decode(encoder.Encode(grey, PngContent::kPhoto)), grey), 0.0);
  EXPECT_EQ(MaxDiff(Decode(encoder.Encode(depth, PngContent::kFlat)), depth), 0.0);
  EXPECT_EQ(MaxDiff(Decode(encoder.Encode(grey, PngContent::kFlat)), grey), 0.0);
  EXPECT_EQ(encoder.Encode(grey, PngContent::kPhoto), EncodePng(grey, PngContent::kPhoto)) << "same bytes as a new encoder";
}

TEST(PngWriter, RejectsOtherTypesAndEmptyImages) {
  EXPECT_THROW(EncodePng(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0)), PngContent::kFlat), RunError);
  EXPECT_THROW(EncodePng(cv::Mat(4, 4, CV_8UC4, cv::Scalar(0)), PngContent::kPhoto), RunError);
  EXPECT_THROW(EncodePng(cv::Mat(), PngContent::kPhoto), RunError);
}

TEST(PngWriter, WriteReportsAnUnwritablePath) {
  PngEncoder encoder;
  const std::string err =
      WritePng("/nonexistent-folder/a.png", cv::Mat(2, 2, CV_8UC1, cv::Scalar(1)), PngContent::kFlat, &encoder);
  EXPECT_NE(err.find("/nonexistent-folder/a.png"), std::string::npos) << err;
  const std::string path = (std::filesystem::temp_directory_path() / "viqu_png_writer.png").string();
  const cv::Mat img(3, 5, CV_8UC1, cv::Scalar(42));
  ASSERT_EQ(WritePng(path, img, PngContent::kFlat, &encoder), "");
  EXPECT_EQ(MaxDiff(cv::imread(path, cv::IMREAD_UNCHANGED), img), 0.0);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace viqu::sim

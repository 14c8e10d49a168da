// Instance masks from an external detector (`viqu slam --masks DIR`, docs/MASKS.md): masks read
// back exactly, a missing mask is "no detections", and every kind of bad mask folder is an
// InputError naming the file. The readers' use of the masks is in test_dataset_io.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/errors.h"
#include "slam/io/instance_mask_folder.h"

namespace viqu::io {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "viqu_masks_XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void WriteText(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << p;
}

// Expects `f` to throw InputError whose message contains every one of `parts`.
template <typename F>
void ExpectInputError(F f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

constexpr int kW = 40, kH = 30;
const cv::Size kSize(kW, kH);

const char* const kInstancesCsv =
    "#id,category,name\n"
    "7,box,box_1\n"
    "300,person,person:alice\n"
    "65535,ball,ball,red\n";

// A mask with a person (300) and a box (7) touching it, and the largest id in a corner.
cv::Mat SampleMask() {
  cv::Mat ids(kSize, CV_16U, cv::Scalar(0));
  ids(cv::Rect(2, 3, 10, 12)).setTo(300);
  ids(cv::Rect(12, 3, 5, 5)).setTo(7);
  ids.at<uint16_t>(kH - 1, kW - 1) = 65535;
  return ids;
}

fs::path MakeFolder(const TempDir& tmp) {
  const fs::path dir = tmp.path() / "masks";
  WriteText(dir / "instances.csv", kInstancesCsv);
  return dir;
}

double MaxAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  return cv::norm(a, b, cv::NORM_INF);
}

TEST(InstanceMaskFolder, ReadsMasksBackExactlyByTheImageFileName) {
  TempDir tmp;
  const fs::path dir = MakeFolder(tmp);
  const cv::Mat want = SampleMask();
  ASSERT_TRUE(cv::imwrite((dir / "1403636579763555584.png").string(), want));
  const InstanceMaskFolder masks(dir.string());

  // Only the file name of the image counts, not its folder.
  const std::string image = "/data/MH_01/mav0/cam0/data/1403636579763555584.png";
  EXPECT_EQ(masks.MaskPath(image), (dir / "1403636579763555584.png").string());
  const cv::Mat got = masks.Read(image, kSize);
  ASSERT_EQ(got.type(), CV_16U);
  EXPECT_EQ(MaxAbsDiff(got, want), 0.0);

  ASSERT_EQ(masks.instances().size(), 3u);  // in order of id
  EXPECT_EQ(masks.instances()[0].id, 7);
  EXPECT_EQ(masks.instances()[0].category, Category::kBox);
  EXPECT_EQ(masks.instances()[0].name, "box_1");
  EXPECT_EQ(masks.instances()[1].id, 300);
  EXPECT_EQ(masks.instances()[1].category, Category::kPerson);
  EXPECT_EQ(masks.instances()[1].name, "person:alice");
  EXPECT_EQ(masks.instances()[2].id, 65535);
  EXPECT_EQ(masks.instances()[2].category, Category::kBall);
  EXPECT_EQ(masks.instances()[2].name, "ball,red");  // the name keeps its commas
}

TEST(InstanceMaskFolder, AMissingMaskMeansNoDetections) {
  TempDir tmp;
  const InstanceMaskFolder masks(MakeFolder(tmp).string());
  const cv::Mat got = masks.Read("rgb/1305031102.175304.png", kSize);
  ASSERT_EQ(got.type(), CV_16U);
  ASSERT_EQ(got.size(), kSize);
  EXPECT_EQ(cv::countNonZero(got), 0);
}

TEST(InstanceMaskFolder, AcceptsAPlainHeaderRowAndAnEmptyList) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "masks";
  WriteText(dir / "instances.csv", "id,category,name\n4,furniture,chair\n");
  const InstanceMaskFolder with_header(dir.string());
  ASSERT_EQ(with_header.instances().size(), 1u);
  EXPECT_EQ(with_header.instances()[0].category, Category::kFurniture);

  WriteText(dir / "instances.csv", "");
  const InstanceMaskFolder empty(dir.string());
  EXPECT_TRUE(empty.instances().empty());
  ASSERT_TRUE(cv::imwrite((dir / "a.png").string(), cv::Mat(kSize, CV_16U, cv::Scalar(0))));
  EXPECT_EQ(cv::countNonZero(empty.Read("a.png", kSize)), 0);  // background only: fine
}

TEST(InstanceMaskFolder, AMaskOfTheWrongSizeNamesTheFile) {
  TempDir tmp;
  const fs::path dir = MakeFolder(tmp);
  const std::string mask = (dir / "f.png").string();
  ASSERT_TRUE(cv::imwrite(mask, cv::Mat(kH, kW + 1, CV_16U, cv::Scalar(0))));
  const InstanceMaskFolder masks(dir.string());
  ExpectInputError([&] { masks.Read("f.png", kSize); }, {mask, "mask is 41x30", "image is 40x30"});
}

TEST(InstanceMaskFolder, AMaskThatIsNotSixteenBitSingleChannelNamesTheFile) {
  TempDir tmp;
  const fs::path dir = MakeFolder(tmp);
  const InstanceMaskFolder masks(dir.string());
  const std::string eight = (dir / "eight.png").string();
  ASSERT_TRUE(cv::imwrite(eight, cv::Mat(kSize, CV_8U, cv::Scalar(7))));
  ExpectInputError([&] { masks.Read("eight.png", kSize); }, {eight, "16-bit single-channel"});
  const std::string colour = (dir / "colour.png").string();
  ASSERT_TRUE(cv::imwrite(colour, cv::Mat(kSize, CV_16UC3, cv::Scalar(7, 7, 7))));
  ExpectInputError([&] { masks.Read("colour.png", kSize); }, {colour, "16-bit single-channel"});
}

TEST(InstanceMaskFolder, ACorruptMaskNamesTheFile) {
  TempDir tmp;
  const fs::path dir = MakeFolder(tmp);
  const InstanceMaskFolder masks(dir.string());
  const std::string truncated = (dir / "t.png").string();
  WriteText(truncated, "\x89PNG\r\n\x1a\n truncated");
  ExpectInputError([&] { masks.Read("t.png", kSize); }, {truncated, "corrupt PNG (truncated"});
  const std::string empty = (dir / "e.png").string();
  WriteText(empty, "");
  ExpectInputError([&] { masks.Read("e.png", kSize); }, {empty, "cannot decode"});
}

TEST(InstanceMaskFolder, AnIdThatInstancesCsvDoesNotListNamesTheFileAndTheId) {
  TempDir tmp;
  const fs::path dir = MakeFolder(tmp);
  cv::Mat ids = SampleMask();
  ids.at<uint16_t>(20, 33) = 8;  // 7 and 300 are listed, 8 is not
  const std::string mask = (dir / "f.png").string();
  ASSERT_TRUE(cv::imwrite(mask, ids));
  const InstanceMaskFolder masks(dir.string());
  ExpectInputError([&] { masks.Read("f.png", kSize); },
                   {mask, "instance id 8", "x=33, y=20", "not listed in " + (dir / "instances.csv").string()});
}

TEST(InstanceMaskFolder, AMissingOrMalformedInstancesCsvNamesTheFile) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "masks";
  const std::string csv = (dir / "instances.csv").string();
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {dir.string(), "masks folder not found"});
  fs::create_directories(dir);
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {csv, "file not found"});
  WriteText(csv, "#id,category,name\n7,box,b\n9,box\n");
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {csv + ":3:", "expected 'id,category,name'"});
  WriteText(csv, "7,car,c\n");
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {csv + ":1:", "unknown category 'car'"});
  WriteText(csv, "70000,box,c\n");
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {csv + ":1:", "not an integer in [0, 65535]"});
  WriteText(csv, "7,box,a\n7,ball,b\n");
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {csv + ":2:", "listed twice"});
  // The header row is only a header in the first row.
  WriteText(csv, "7,box,a\nid,category,name\n");
  ExpectInputError([&] { InstanceMaskFolder m(dir.string()); }, {csv + ":2:", "id 'id'"});
}

}  // namespace
}  // namespace viqu::io

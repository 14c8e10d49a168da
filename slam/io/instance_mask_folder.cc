#include "slam/io/instance_mask_folder.h"

#include <cstdint>
#include <filesystem>

#include "common/errors.h"
#include "slam/io/image_files.h"
#include "slam/io/segment_instances.h"

namespace viqu::io {

namespace fs = std::filesystem;

InstanceMaskFolder::InstanceMaskFolder(const std::string& dir)
    : dir_(dir), csv_path_((fs::path(dir) / "instances.csv").string()), listed_(65536, false) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": masks folder not found");
  instances_ = ReadSegmentInstances(csv_path_);
  for (const SegmentInstance& inst : instances_) listed_[inst.id] = true;
}

std::string InstanceMaskFolder::MaskPath(const std::string& image_path) const {
  return (fs::path(dir_) / fs::path(image_path).filename()).string();
}

cv::Mat InstanceMaskFolder::Read(const std::string& image_path, const cv::Size& image_size) const {
  const std::string path = MaskPath(image_path);
  std::error_code ec;
  if (!fs::exists(path, ec)) return cv::Mat(image_size, CV_16U, cv::Scalar(0));
  std::string why;
  cv::Mat ids = ReadImage16(path, &why);
  if (ids.empty()) throw InputError(why);
  if (ids.size() != image_size) {
    throw InputError(path + ": mask is " + std::to_string(ids.cols) + "x" + std::to_string(ids.rows) +
                     ", its image is " + std::to_string(image_size.width) + "x" + std::to_string(image_size.height));
  }
  CheckIdsListed(ids, path);
  return ids;
}

void InstanceMaskFolder::CheckIdsListed(const cv::Mat& ids, const std::string& mask_path) const {
  for (int v = 0; v < ids.rows; ++v) {
    const uint16_t* row = ids.ptr<uint16_t>(v);
    for (int u = 0; u < ids.cols; ++u) {
      if (row[u] != 0 && !listed_[row[u]]) {
        throw InputError(mask_path + ": instance id " + std::to_string(row[u]) + " (first at x=" + std::to_string(u) +
                         ", y=" + std::to_string(v) + ") is not listed in " + csv_path_);
      }
    }
  }
}

}  // namespace viqu::io

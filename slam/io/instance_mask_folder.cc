#include "slam/io/instance_mask_folder.h"

#include <filesystem>

#include "common/errors.h"
#include "slam/io/image_files.h"
#include "slam/io/segment_instances.h"

namespace viqu::io {

namespace fs = std::filesystem;

InstanceMaskFolder::InstanceMaskFolder(const std::string& dir)
    : dir_(dir), csv_path_((fs::path(dir) / "instances.csv").string()) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": masks folder not found");
  instances_ = ReadSegmentInstances(csv_path_);
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
  CheckIdsListed(ids, instances_, path, "in " + csv_path_);
  return ids;
}

}  // namespace viqu::io

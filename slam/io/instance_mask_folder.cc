#include "slam/io/instance_mask_folder.h"

#include <filesystem>

#include "common/errors.h"
#include "common/input_file.h"
#include "slam/io/image_files.h"
#include "slam/io/segment_instances.h"

namespace viqu::io {

namespace fs = std::filesystem;

uintmax_t MaxMaskFileBytes(const cv::Size& image_size) {
  const uintmax_t raw = uintmax_t{2} * static_cast<uintmax_t>(image_size.area());
  return 2 * raw + (uintmax_t{1} << 20);
}

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
  // No file of that name: the detector found nothing in the frame. Anything under the name that
  // cannot be read (a dangling link, a loop of links, a folder, a device) is a broken mask, not
  // "no detections".
  std::error_code ec;
  const fs::file_status entry = fs::symlink_status(path, ec);
  if (entry.type() == fs::file_type::not_found) return cv::Mat(image_size, CV_16U, cv::Scalar(0));
  CheckInputFile(path, MaxMaskFileBytes(image_size), "mask image");
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

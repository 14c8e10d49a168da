#pragma once
// Per-frame instance masks made by an external detector, for `viqu slam --masks DIR`
// (docs/MASKS.md): DIR/<file name of the frame's image> is a 16-bit single-channel PNG of
// instance ids (0 = background) in the geometry of that image as stored, and DIR/instances.csv
// ("id,category,name", as a viqu recording's seg0/instances.csv) describes the ids.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "slam/measurements/stereo_frame.h"

namespace viqu::io {

// The largest mask file read for an image size (bytes): twice the raw 16-bit pixels plus 1 MiB.
// A PNG stores incompressible data with a few bytes per 64 KiB block and one per row, so no
// honest mask comes near it; 200 MB of data behind a 640x480 header is refused.
uintmax_t MaxMaskFileBytes(const cv::Size& image_size);

class InstanceMaskFolder {
 public:
  // Reads DIR/instances.csv. Missing folder or file, malformed row: InputError naming it.
  explicit InstanceMaskFolder(const std::string& dir);

  // The ids (CV_16U, `image_size`) of the frame whose image file is `image_path` (only its file
  // name is used). No mask file: no detections, all zero. A mask that is no readable regular
  // file (a dangling link, a loop of links, a folder), is larger than MaxMaskFileBytes, cannot
  // be decoded, is not 16-bit single-channel, differs from `image_size` or holds an id that
  // instances.csv does not list: InputError naming the mask file.
  cv::Mat Read(const std::string& image_path, const cv::Size& image_size) const;

  // The mask file for an image file: DIR/<file name of image_path>.
  std::string MaskPath(const std::string& image_path) const;

  // Every row of instances.csv, in order of id.
  const std::vector<SegmentInstance>& instances() const { return instances_; }

 private:
  std::string dir_;                         // the masks folder
  std::string csv_path_;                    // DIR/instances.csv
  std::vector<SegmentInstance> instances_;  // its rows
};

}  // namespace viqu::io

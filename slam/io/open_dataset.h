#pragma once
#include <memory>
#include <string>

#include "slam/io/dataset_reader.h"

namespace viqu::io {

enum class DatasetFormat {
  kViqu,   // a run folder recorded by `viqu run --record` (RUN/ or RUN/dataset/)
  kEuroc,  // EuRoC MAV (mav0/cam0, cam1), rectified on reading
  kTum,    // TUM RGB-D (rgb.txt, depth.txt, groundtruth.txt)
};

// "viqu", "euroc", "tum". Anything else: InputError listing the choices.
DatasetFormat ParseDatasetFormat(const std::string& name);
const char* DatasetFormatName(DatasetFormat format);

// Opens the dataset in `dir`; with `masks_dir` (not "") its frames carry the instance masks of
// that folder (InstanceMaskFolder, docs/MASKS.md), which replace a viqu recording's seg0.
// Missing or malformed input: InputError naming the file.
// `camera_file` (not ""): the calibration of a TUM-format folder (ReadCameraFile); other formats
// carry theirs in sensor.yaml and refuse one (InputError).
std::unique_ptr<DatasetReader> OpenDataset(const std::string& dir, DatasetFormat format,
                                           const std::string& masks_dir = "", const std::string& camera_file = "");

}  // namespace viqu::io

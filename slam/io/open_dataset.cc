#include "slam/io/open_dataset.h"

#include "common/errors.h"
#include "common/run_folder.h"
#include "slam/io/euroc_dataset_reader.h"
#include "slam/io/tum_dataset_reader.h"
#include "slam/io/viqu_dataset_reader.h"

namespace viqu::io {

DatasetFormat ParseDatasetFormat(const std::string& name) {
  if (name == "viqu") return DatasetFormat::kViqu;
  if (name == "euroc") return DatasetFormat::kEuroc;
  if (name == "tum") return DatasetFormat::kTum;
  throw InputError("unknown dataset format '" + name + "' (expected one of: viqu, euroc, tum)");
}

const char* DatasetFormatName(DatasetFormat format) {
  switch (format) {
    case DatasetFormat::kViqu: return "viqu";
    case DatasetFormat::kEuroc: return "euroc";
    case DatasetFormat::kTum: return "tum";
  }
  return "unknown";
}

std::unique_ptr<DatasetReader> OpenDataset(const std::string& dir, DatasetFormat format,
                                           const std::string& masks_dir, const std::string& camera_file) {
  // A dataset recorded by a run that did not finish, or a run folder without its completion
  // marker, is refused before anything is read.
  RequireNotInIncompleteRun(dir);
  if (!camera_file.empty() && format != DatasetFormat::kTum) {
    throw InputError(camera_file + ": --camera applies to TUM-format folders; " + std::string(DatasetFormatName(format)) +
                     " recordings carry their calibration in mav0/cam0/sensor.yaml and cam1/sensor.yaml");
  }
  switch (format) {
    case DatasetFormat::kViqu: return std::make_unique<ViquDatasetReader>(dir, masks_dir);
    case DatasetFormat::kEuroc: return std::make_unique<EurocDatasetReader>(dir, masks_dir);
    case DatasetFormat::kTum: return std::make_unique<TumDatasetReader>(dir, masks_dir, camera_file);
  }
  throw InputError("unknown dataset format");
}

}  // namespace viqu::io

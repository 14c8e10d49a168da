#include "slam/io/euroc_layout.h"

#include <filesystem>

#include "common/errors.h"

namespace viqu::io {

namespace fs = std::filesystem;

std::string FindMav0(const std::string& dir) {
  std::error_code ec;
  fs::path d = fs::path(dir).lexically_normal();
  if (d.filename().empty()) d = d.parent_path();  // "x/mav0/" -> "x/mav0"
  if (!fs::is_directory(d, ec)) throw InputError(dir + ": dataset folder not found");
  if (d.filename() == "mav0" || fs::is_regular_file(d / "cam0" / "data.csv", ec)) return d.string();
  if (fs::is_directory(d / "mav0", ec)) return (d / "mav0").string();
  throw InputError(dir + ": no mav0/ folder (expected the EuRoC MAV layout DIR/mav0/cam0/data.csv)");
}

EurocStereoLayout ReadEurocStereoLayout(const std::string& mav0) {
  EurocStereoLayout out;
  out.mav0 = mav0;
  const fs::path m(mav0);
  out.cam0 = ReadEurocCameraSensor((m / "cam0" / "sensor.yaml").string());
  out.cam1 = ReadEurocCameraSensor((m / "cam1" / "sensor.yaml").string());
  const std::string csv0 = (m / "cam0" / "data.csv").string(), csv1 = (m / "cam1" / "data.csv").string();
  const std::vector<ImageEntry> left = ReadEurocImageList(csv0, (m / "cam0" / "data").string());
  const std::vector<ImageEntry> right = ReadEurocImageList(csv1, (m / "cam1" / "data").string());
  if (left.empty()) throw InputError(csv0 + ": no images listed (empty dataset)");
  if (right.empty()) throw InputError(csv1 + ": no images listed (empty dataset)");
  out.frames = PairEqualStamps(left, right, csv0, csv1);
  if (out.frames.empty()) throw InputError(csv0 + ": no image has a partner with the same stamp in " + csv1);
  return out;
}

}  // namespace viqu::io

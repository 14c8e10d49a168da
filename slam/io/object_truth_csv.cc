#include "slam/io/object_truth_csv.h"

#include <filesystem>

#include "slam/io/number_parsing.h"
#include "slam/io/segment_instances.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {

std::optional<ObjectTruthStream> ReadViquObjectTruth(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path mav0 = fs::path(dir) / "dataset" / "mav0";
  if (!fs::is_directory(mav0, ec)) mav0 = fs::path(dir) / "mav0";
  const fs::path csv = mav0 / "objects0" / "data.csv";
  if (fs::symlink_status(csv, ec).type() == fs::file_type::not_found) return std::nullopt;
  TextTableReader table(csv.string(), ',');
  ObjectTruthStream out;
  std::vector<std::string> f;
  int64_t last = 0;
  while (table.Next(&f)) {
    if (f.size() < 5) table.Fail("expected 'timestamp [ns],visible_px,truly_moving,category,name'");
    int64_t t = 0, px = 0;
    if (!ParseInt64(f[0], &t)) table.Fail("timestamp '" + f[0] + "' is not an integer (ns)");
    if (!out.empty() && t < last) table.Fail("timestamp " + f[0] + " goes backwards (after " + std::to_string(last) + ")");
    last = t;
    ObjectTruth o;
    if (!ParseInt64(f[1], &px) || px < 0 || px > (int64_t{1} << 30)) table.Fail("visible_px '" + f[1] + "' is not a pixel count");
    o.visible_px = static_cast<int>(px);
    if (f[2] != "0" && f[2] != "1") table.Fail("truly_moving must be 0 or 1, got '" + f[2] + "'");
    o.moving = f[2] == "1";
    if (!ParseCategory(f[3], &o.category)) table.Fail("unknown category '" + f[3] + "'");
    o.name = f[4];
    for (size_t i = 5; i < f.size(); ++i) o.name += "," + f[i];
    out[t].push_back(std::move(o));
  }
  return out;
}

}  // namespace viqu::io

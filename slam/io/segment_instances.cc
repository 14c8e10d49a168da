#include "slam/io/segment_instances.h"

#include <algorithm>
#include <cstdint>

#include "slam/io/number_parsing.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {
namespace {

bool ParseCategory(const std::string& name, Category* out) {
  for (int c = 0; c <= static_cast<int>(Category::kRobot); ++c) {
    if (name == CategoryName(static_cast<Category>(c))) {
      *out = static_cast<Category>(c);
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<SegmentInstance> ReadSegmentInstances(const std::string& csv_path) {
  TextTableReader table(csv_path, ',');
  std::vector<SegmentInstance> out;
  std::vector<std::string> f;
  bool first_row = true;
  while (table.Next(&f)) {
    const bool header = first_row && f.size() == 3 && f[0] == "id" && f[1] == "category" && f[2] == "name";
    first_row = false;
    if (header) continue;  // a header row without '#', as CSV writers emit it
    if (f.size() < 3) table.Fail("expected 'id,category,name'");
    int64_t id = 0;
    if (!ParseInt64(f[0], &id) || id < 0 || id > 65535) table.Fail("id '" + f[0] + "' is not an integer in [0, 65535]");
    SegmentInstance inst;
    inst.id = static_cast<uint16_t>(id);
    if (!ParseCategory(f[1], &inst.category)) table.Fail("unknown category '" + f[1] + "'");
    inst.name = f[2];
    for (size_t i = 3; i < f.size(); ++i) inst.name += "," + f[i];
    for (const SegmentInstance& other : out) {
      if (other.id == inst.id) table.Fail("id " + f[0] + " is listed twice");
    }
    out.push_back(std::move(inst));
  }
  std::sort(out.begin(), out.end(), [](const SegmentInstance& a, const SegmentInstance& b) { return a.id < b.id; });
  return out;
}

std::vector<SegmentInstance> InstancesPresent(const cv::Mat& ids, const std::vector<SegmentInstance>& all) {
  std::vector<bool> seen(65536, false);
  for (int r = 0; r < ids.rows; ++r) {
    const uint16_t* row = ids.ptr<uint16_t>(r);
    for (int c = 0; c < ids.cols; ++c) seen[row[c]] = true;
  }
  std::vector<SegmentInstance> out;
  for (const SegmentInstance& inst : all) {
    if (seen[inst.id]) out.push_back(inst);
  }
  return out;
}

}  // namespace viqu::io

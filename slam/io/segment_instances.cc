#include "slam/io/segment_instances.h"

#include <algorithm>
#include <cstdint>

#include "common/errors.h"
#include "slam/io/number_parsing.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {

bool ParseCategory(const std::string& name, Category* out) {
  for (int c = 0; c <= static_cast<int>(Category::kRobot); ++c) {
    if (name == CategoryName(static_cast<Category>(c))) {
      *out = static_cast<Category>(c);
      return true;
    }
  }
  return false;
}

namespace {

// Parses "id,category,name..." from fields[first...] into *out; false with *why on bad input.
bool ParseInstance(const std::vector<std::string>& f, size_t first, SegmentInstance* out, std::string* why) {
  int64_t id = 0;
  if (!ParseInt64(f[first], &id) || id < 0 || id > 65535) {
    *why = "id '" + f[first] + "' is not an integer in [0, 65535]";
    return false;
  }
  out->id = static_cast<uint16_t>(id);
  if (!ParseCategory(f[first + 1], &out->category)) {
    *why = "unknown category '" + f[first + 1] + "'";
    return false;
  }
  out->name = f[first + 2];
  for (size_t i = first + 3; i < f.size(); ++i) out->name += "," + f[i];
  return true;
}

bool ById(const SegmentInstance& a, const SegmentInstance& b) { return a.id < b.id; }

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
    SegmentInstance inst;
    std::string why;
    if (!ParseInstance(f, 0, &inst, &why)) table.Fail(why);
    for (const SegmentInstance& other : out) {
      if (other.id == inst.id) table.Fail("id " + f[0] + " is listed twice");
    }
    out.push_back(std::move(inst));
  }
  std::sort(out.begin(), out.end(), ById);
  return out;
}

std::map<int64_t, std::vector<SegmentInstance>> ReadFrameInstances(const std::string& csv_path) {
  TextTableReader table(csv_path, ',');
  std::map<int64_t, std::vector<SegmentInstance>> out;
  std::vector<std::string> f;
  int64_t last_t_ns = 0;
  std::vector<SegmentInstance>* list = nullptr;  // the current stamp's list
  while (table.Next(&f)) {
    if (f.size() < 4) table.Fail("expected 'timestamp [ns],id,category,name'");
    int64_t t_ns = 0;
    if (!ParseInt64(f[0], &t_ns)) table.Fail("timestamp '" + f[0] + "' is not an integer (ns)");
    SegmentInstance inst;
    std::string why;
    if (!ParseInstance(f, 1, &inst, &why)) table.Fail(why);
    if (list == nullptr || t_ns != last_t_ns) {
      if (list != nullptr && t_ns < last_t_ns) {
        table.Fail("timestamp " + f[0] + " follows " + std::to_string(last_t_ns) +
                   " (rows must be in time order, those of one stamp together)");
      }
      list = &out[t_ns];
      last_t_ns = t_ns;
    }
    for (const SegmentInstance& other : *list) {
      if (other.id == inst.id) table.Fail("id " + f[1] + " is listed twice for timestamp " + f[0]);
    }
    list->push_back(std::move(inst));
  }
  for (auto& [t_ns, instances] : out) std::sort(instances.begin(), instances.end(), ById);
  return out;
}

void CheckIdsListed(const cv::Mat& ids, const std::vector<SegmentInstance>& listed, const std::string& image_path,
                    const std::string& list_what) {
  std::vector<bool> known(65536, false);
  for (const SegmentInstance& inst : listed) known[inst.id] = true;
  for (int v = 0; v < ids.rows; ++v) {
    const uint16_t* row = ids.ptr<uint16_t>(v);
    for (int u = 0; u < ids.cols; ++u) {
      if (row[u] != 0 && !known[row[u]]) {
        throw InputError(image_path + ": instance id " + std::to_string(row[u]) + " (first at x=" + std::to_string(u) +
                         ", y=" + std::to_string(v) + ") is not listed " + list_what);
      }
    }
  }
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

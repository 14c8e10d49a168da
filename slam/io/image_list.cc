#include "slam/io/image_list.h"

#include <cstdio>
#include <filesystem>

#include "slam/eval/trajectory.h"
#include "slam/io/number_parsing.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {
namespace {

constexpr int kMaxWarnings = 5;  // unpaired images named one by one; beyond that, a count

// Reads "stamp<sep>filename" rows; `seconds` chooses TUM seconds over EuRoC nanoseconds.
std::vector<ImageEntry> ReadList(const std::string& path, const std::string& dir, char separator, bool seconds) {
  TextTableReader table(path, separator);
  std::vector<ImageEntry> out;
  std::vector<std::string> f;
  while (table.Next(&f)) {
    if (f.size() != 2 || f[1].empty()) {
      table.Fail(seconds ? "expected 'timestamp filename'" : "expected 'timestamp [ns],filename'");
    }
    ImageEntry e;
    const bool ok = seconds ? ParseSecondsAsNs(f[0], &e.t_ns) : ParseInt64(f[0], &e.t_ns);
    if (!ok) {
      table.Fail("timestamp '" + f[0] + "' is not " + (seconds ? "a number of seconds" : "an integer (ns)"));
    }
    if (!out.empty() && e.t_ns <= out.back().t_ns) {
      table.Fail(std::string(e.t_ns < out.back().t_ns ? "timestamp goes backwards" : "timestamp repeats") +
                 " (" + f[0] + " after the previous row)");
    }
    e.path = (std::filesystem::path(dir) / f[1]).string();
    out.push_back(std::move(e));
  }
  return out;
}

void WarnUnpaired(int count, const std::string& name, const std::string& other, const std::vector<int64_t>& shown) {
  if (count == 0) return;
  for (int64_t t : shown) {
    std::fprintf(stderr, "viqu: warning: %s: image at %lld ns has no partner in %s; skipped\n", name.c_str(),
                 static_cast<long long>(t), other.c_str());
  }
  if (count > static_cast<int>(shown.size())) {
    std::fprintf(stderr, "viqu: warning: %s: %d images in all have no partner in %s; skipped\n", name.c_str(),
                 count, other.c_str());
  }
}

}  // namespace

std::vector<ImageEntry> ReadEurocImageList(const std::string& csv_path, const std::string& data_dir) {
  return ReadList(csv_path, data_dir, ',', false);
}

std::vector<ImageEntry> ReadTumImageList(const std::string& txt_path, const std::string& base_dir) {
  return ReadList(txt_path, base_dir, ' ', true);
}

std::vector<ImagePair> PairEqualStamps(const std::vector<ImageEntry>& a, const std::vector<ImageEntry>& b,
                                       const std::string& a_name, const std::string& b_name) {
  std::vector<ImagePair> pairs;
  int unpaired_a = 0, unpaired_b = 0;
  std::vector<int64_t> shown_a, shown_b;
  size_t j = 0;
  for (const ImageEntry& e : a) {
    while (j < b.size() && b[j].t_ns < e.t_ns) {
      if (++unpaired_b <= kMaxWarnings) shown_b.push_back(b[j].t_ns);
      ++j;
    }
    if (j < b.size() && b[j].t_ns == e.t_ns) {
      pairs.push_back({e.t_ns, e.path, b[j].path});
      ++j;
    } else if (++unpaired_a <= kMaxWarnings) {
      shown_a.push_back(e.t_ns);
    }
  }
  for (; j < b.size(); ++j) {
    if (++unpaired_b <= kMaxWarnings) shown_b.push_back(b[j].t_ns);
  }
  WarnUnpaired(unpaired_a, a_name, b_name, shown_a);
  WarnUnpaired(unpaired_b, b_name, a_name, shown_b);
  return pairs;
}

std::vector<ImagePair> PairNearestStamps(const std::vector<ImageEntry>& a, const std::vector<ImageEntry>& b,
                                         double max_diff_s, const std::string& a_name,
                                         const std::string& b_name) {
  // eval::Associate implements associate.py on stamped poses; only the stamps matter here.
  eval::Trajectory ta(a.size()), tb(b.size());
  for (size_t i = 0; i < a.size(); ++i) ta[i].t_ns = a[i].t_ns;
  for (size_t i = 0; i < b.size(); ++i) tb[i].t_ns = b[i].t_ns;
  std::vector<ImagePair> pairs;
  for (const auto& [i, j] : eval::Associate(ta, tb, max_diff_s)) pairs.push_back({a[i].t_ns, a[i].path, b[j].path});
  if (pairs.size() < a.size()) {
    std::fprintf(stderr, "viqu: warning: %s: %zu of %zu images have no partner in %s within %.3f s; skipped\n",
                 a_name.c_str(), a.size() - pairs.size(), a.size(), b_name.c_str(), max_diff_s);
  }
  return pairs;
}

}  // namespace viqu::io

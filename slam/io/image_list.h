#pragma once
// Lists of timestamped image files: EuRoC data.csv ("t_ns,filename") and TUM rgb.txt/depth.txt
// ("t_s filename"), and the association of two lists.
#include <cstdint>
#include <string>
#include <vector>

namespace viqu::io {

struct ImageEntry {
  int64_t t_ns = 0;   // stamp (ns)
  std::string path;   // the image file
};

// Reads a EuRoC data.csv; file names are taken relative to `data_dir`. Malformed row (not
// "integer,name"), stamp that does not increase: InputError "CSV:LINE: ...". May return empty.
std::vector<ImageEntry> ReadEurocImageList(const std::string& csv_path, const std::string& data_dir);

// Reads a TUM list ("timestamp filename", seconds); file names are relative to `base_dir`.
// Same errors as ReadEurocImageList.
std::vector<ImageEntry> ReadTumImageList(const std::string& txt_path, const std::string& base_dir);

// Image pairs (a from `a`, b from `b`) in the time order of `a`.
struct ImagePair {
  int64_t t_ns = 0;  // stamp of the `a` image (ns)
  std::string a, b;  // paths
};

// Pairs images with equal stamps (EuRoC stereo). Images without partner are left out with a
// warning on stderr naming `a_name`/`b_name` (at most a few lines, then a count).
std::vector<ImagePair> PairEqualStamps(const std::vector<ImageEntry>& a, const std::vector<ImageEntry>& b,
                                       const std::string& a_name, const std::string& b_name);

// Pairs images as TUM's associate.py does: nearest stamps within max_diff_s, greedy by smallest
// difference, each image used once. Images of `a` without partner are left out with one
// warning on stderr.
std::vector<ImagePair> PairNearestStamps(const std::vector<ImageEntry>& a, const std::vector<ImageEntry>& b,
                                         double max_diff_s, const std::string& a_name,
                                         const std::string& b_name);

}  // namespace viqu::io

#pragma once
#include <string>

namespace viqu {

// Writes `content` to `path` through a temporary file in the same folder and a rename, so that
// `path` either keeps its old content or holds the whole new content. Throws RunError on failure.
void WriteFileAtomic(const std::string& path, const std::string& content);

// Renames a finished temporary file onto its final name (same folder). Throws RunError.
void CommitTempFile(const std::string& tmp_path, const std::string& final_path);

// Renames a finished folder `from` onto `to`. An existing `to` is moved aside first and removed
// once the new one is in place, so `to` is never half old, half new. Throws RunError.
void CommitTempDirectory(const std::string& from, const std::string& to);

// The temporary name used for `path` while it is being written.
std::string TempPathFor(const std::string& path);

}  // namespace viqu

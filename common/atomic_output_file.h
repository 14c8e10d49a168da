#pragma once
#include <cstdio>
#include <string>

namespace viqu {

// A text or binary output file written under a temporary name (TempPathFor, same folder) and
// renamed onto its final name by Commit(). Destroyed without Commit(), it removes the
// temporary file, so the final name never holds a half-written file.
class AtomicOutputFile {
 public:
  // Opens the temporary file. Throws RunError when it cannot be created.
  explicit AtomicOutputFile(const std::string& final_path);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  // Appends bytes. Throws RunError on a write error.
  void Write(const std::string& text);
  // Flushes, closes and renames onto the final name. Throws RunError on failure.
  void Commit();

  bool committed() const { return committed_; }
  const std::string& final_path() const { return final_path_; }
  const std::string& temp_path() const { return temp_path_; }

 private:
  std::string final_path_;    // where the file ends up
  std::string temp_path_;     // where it is written meanwhile
  std::FILE* file_ = nullptr; // open temporary file; null after Commit()
  bool committed_ = false;    // renamed onto final_path_
};

}  // namespace viqu

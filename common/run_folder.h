#pragma once
#include <memory>
#include <string>
#include <vector>

#include "common/output_lock.h"

namespace viqu {

// The completion marker: written last into a run folder that finished (exit code 0 or 1), it
// lists every file with its size. A folder without it is incomplete, and every reader refuses it.
inline constexpr const char* kRunCompleteMarker = "run_complete.json";
// Written instead of the completion marker by a run that was interrupted (SIGINT, SIGTERM): the
// outputs up to the interruption are there to look at, and the marker says why they stop.
inline constexpr const char* kRunIncompleteMarker = "run_incomplete.json";

// Policy (DESIGN.md, run folder): a run writes into a fresh sibling folder DIR.partial-PID and,
// when it ends, that folder replaces DIR as a whole. So one run's files can never sit beside
// another's, a failed run leaves DIR as it was, and a killed run leaves only the partial folder
// (no marker: recognisably incomplete), which the next run into DIR removes.
//
//   RunFolderWriter folder(opt.out_dir, opt.force, command_line, {scenario_file, world_file});
//   ... write outputs under folder.path() ...
//   folder.Complete(exit_code);       // or folder.Interrupted("SIGINT at t = 3.2 s")
class RunFolderWriter {
 public:
  // Throws InputError (exit 2) when DIR is a file, the current folder or one above it, holds one
  // of `inputs` or lies inside one (RequireOutsideOutput; `force` does not lift either), is a
  // non-empty folder that holds no viqu run (unless `force`), when another process writes DIR
  // (OutputLock, held until this writer is destroyed; `force` does not lift it), or when the
  // partial folder cannot be created (e.g. an unwritable parent). Removes partial folders of
  // earlier runs into DIR whose process is gone.
  RunFolderWriter(const std::string& final_dir, bool force, const std::string& command_line,
                  const std::vector<std::string>& inputs = {});
  // Without Complete() or Interrupted() (an exception): removes the partial folder.
  ~RunFolderWriter();
  RunFolderWriter(const RunFolderWriter&) = delete;
  RunFolderWriter& operator=(const RunFolderWriter&) = delete;

  // Where outputs go while the run works.
  const std::string& path() const { return partial_; }
  // Where they end up.
  const std::string& final_path() const { return final_; }

  // Writes the completion marker (the run's exit code, every file with its size) and swaps the
  // folder in. Throws RunError on a file-system failure.
  void Complete(int exit_code);
  // Writes the incomplete marker with `reason` and swaps the folder in.
  void Interrupted(const std::string& reason);

 private:
  void SwapIn();

  std::string final_;
  std::string partial_;
  std::string command_line_;
  bool done_ = false;
  std::unique_ptr<OutputLock> lock_;  // DIR's, from the checks until destruction
};

// Throws InputError when `input` (a file or folder the run reads while it works) lies in
// `out_dir`, which the run replaces as a whole, or when `out_dir` lies inside the folder `input`
// (writing there would change what is read: a recorded run's files no longer match its marker).
// Empty `input`: nothing to check.
void RequireOutsideOutput(const std::string& out_dir, const std::string& input);

// "DIR/{a.txt,b.json,plots/,...}": what the folder holds at its top level, sorted (folders with a
// trailing '/'), for the line a command prints when it ends.
std::string OutputsLine(const std::string& dir);

// Whether `dir` holds a complete run: the completion marker is there and every file it lists is
// there with its size. Otherwise false with the reason in `why` (when given).
bool IsCompleteRunFolder(const std::string& dir, std::string* why = nullptr);
// Throws InputError naming `dir` and the reason when it is not a complete run folder.
void RequireCompleteRunFolder(const std::string& dir);
// Whether `dir` looks like a viqu run folder (a marker, or the files of a run written before
// markers existed), complete or not.
bool LooksLikeRunFolder(const std::string& dir);
// For readers of single files (trajectories, datasets): throws InputError when `path` lies in a
// viqu run folder (its own folder or the one above) that is not complete.
void RequireNotInIncompleteRun(const std::string& path);

}  // namespace viqu

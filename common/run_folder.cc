#include "common/run_folder.h"


#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/json_writer.h"
#include "common/yaml_strict.h"

namespace viqu {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPartialInfix = ".partial-";
constexpr int kMarkerFormat = 1;  // version of the markers' layout

// Everything a run or a replay writes at a folder's top level: a folder that holds nothing else
// (and a marker or a metrics.json) is ours to replace without --force.
const char* const kOwnedNames[] = {"scenario.yaml", "metrics.json", "slam_settings.yaml", "trajectory_gt.txt",
                                   "trajectory_est.txt", "trajectory_lo.txt", "tracking.csv", "dynamic.csv",
                                   "lo.csv", "slip.csv", "contact.csv", "dataset", "dataset_tum", "video.mp4", "plots",
                                   "run_complete.json", "run_incomplete.json"};

// Whether every entry of `dir` is one a run writes (or a temporary of one), with a marker or a
// metrics.json among them.
bool HoldsOnlyRunOutputs(const fs::path& dir) {
  std::error_code ec;
  bool ours = false;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") != std::string::npos) continue;
    bool known = false;
    for (const char* n : kOwnedNames) known = known || name == n;
    if (!known) return false;
    ours = ours || name == "metrics.json" || name == kRunCompleteMarker || name == kRunIncompleteMarker;
  }
  return ours && !ec;
}

// Every regular file under `dir`, relative to it, sorted (the marker lists them deterministically).
std::vector<std::pair<std::string, uintmax_t>> ListFiles(const std::string& dir) {
  std::vector<std::pair<std::string, uintmax_t>> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    files.emplace_back(fs::relative(e.path(), dir).generic_string(), e.file_size());
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool ProcessAlive(long pid) {
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

// Cleans up after runs into DIR whose process no longer exists: a DIR.partial-PID folder is
// removed, unless it holds a completion marker and DIR is missing (the run was killed between
// the two renames of the swap): then it is the run's result and is put in place. A DIR.old.PID
// folder (the previous run, moved aside by a swap that never finished) goes back to DIR when DIR
// is missing, else it is removed.
void RemoveStalePartials(const fs::path& final_dir) {
  std::error_code ec;
  const fs::path parent = final_dir.parent_path().empty() ? fs::path(".") : final_dir.parent_path();
  for (const std::string& infix : {std::string(kPartialInfix), std::string(".old.")}) {
    const std::string prefix = final_dir.filename().string() + infix;
    std::vector<fs::path> stale;
    for (const fs::directory_entry& e : fs::directory_iterator(parent, ec)) {
      const std::string name = e.path().filename().string();
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid_text = name.substr(prefix.size());
      if (pid_text.empty() || pid_text.size() > 9 || !std::all_of(pid_text.begin(), pid_text.end(), ::isdigit)) continue;
      if (!ProcessAlive(std::stol(pid_text))) stale.push_back(e.path());
    }
    for (const fs::path& p : stale) {
      std::error_code rm;
      const bool finished = infix == ".old." || fs::exists(p / kRunCompleteMarker, rm);
      if (finished && !fs::exists(final_dir, rm)) {
        fs::rename(p, final_dir, rm);
        if (!rm) continue;
      }
      fs::remove_all(p, rm);
    }
  }
}

// Whether `a` is `b` or a folder above it.
bool IsSameOrAncestor(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  // Absolute first: weakly_canonical leaves a relative path relative when its first part does not
  // exist (a default --out "runs/..." before runs/ is made), which would compare with nothing.
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  auto ia = ca.begin(), ib = cb.begin();
  for (; ia != ca.end(); ++ia, ++ib) {
    if (ib == cb.end() || *ia != *ib) return ia->empty() && std::next(ia) == ca.end();  // trailing '/'
  }
  return true;
}

void WriteMarker(const std::string& dir, const char* name, const std::string& status, const std::string& command,
                 const int* exit_code, const std::string& reason) {
  JsonWriter j;
  j.Set("viqu_run_folder", kMarkerFormat);
  j.Set("status", status);
  j.Set("command", command);
  if (exit_code) j.Set("exit_code", *exit_code);
  if (!reason.empty()) j.Set("reason", reason);
  j.EnsureArray("files");
  for (const auto& [path, bytes] : ListFiles(dir)) {
    JsonWriter f;
    f.Set("path", path);
    f.Set("bytes", static_cast<uint64_t>(bytes));
    j.Append("files", f);
  }
  WriteFileAtomic(dir + "/" + name, j.ToString());
}

}  // namespace

RunFolderWriter::RunFolderWriter(const std::string& final_dir, bool force, const std::string& command_line,
                                 const std::vector<std::string>& inputs)
    : command_line_(command_line) {
  fs::path dir = fs::path(final_dir).lexically_normal();
  if (!dir.empty() && !dir.has_filename() && dir.has_relative_path()) dir = dir.parent_path();  // "runs/x/" -> "runs/x"
  final_ = dir.string();
  std::error_code ec;
  if (dir.empty() || !dir.has_relative_path()) {
    throw InputError("output folder '" + final_dir + "': not a folder a run can replace (empty or a root)");
  }
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InputError("output folder " + final_ + " exists and is not a folder");
  }
  if (IsSameOrAncestor(dir, fs::current_path(ec))) {
    throw InputError("output folder " + final_ + " is the current folder or holds it; a run replaces its folder as a whole");
  }
  for (const std::string& input : inputs) RequireOutsideOutput(final_, input);
  // One writer at a time: a second command into DIR stops here, before it touches anything.
  lock_ = std::make_unique<OutputLock>(final_, command_line_.size() > 300 ? command_line_.substr(0, 300) + "..." : command_line_);
  if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec) && !HoldsOnlyRunOutputs(dir) && !force) {
    throw InputError("output folder " + final_ +
                     " holds files that are no viqu run's outputs; a run replaces its folder as a whole: choose another "
                     "--out or pass --force");
  }
  if (!dir.parent_path().empty()) {
    fs::create_directories(dir.parent_path(), ec);
    if (ec) throw InputError("cannot create output folder " + final_ + ": " + ec.message());
  }
  RemoveStalePartials(dir);
  partial_ = final_ + kPartialInfix + std::to_string(::getpid());
  fs::remove_all(partial_, ec);
  fs::create_directory(partial_, ec);
  if (ec) throw InputError("cannot create output folder " + final_ + " (" + partial_ + "): " + ec.message());
}

RunFolderWriter::~RunFolderWriter() {
  if (done_) return;
  std::error_code ec;
  fs::remove_all(partial_, ec);
}

void RunFolderWriter::Complete(int exit_code) {
  WriteMarker(partial_, kRunCompleteMarker, "complete", command_line_, &exit_code, "");
  SwapIn();
}

void RunFolderWriter::Interrupted(const std::string& reason) {
  WriteMarker(partial_, kRunIncompleteMarker, "interrupted", command_line_, nullptr, reason);
  SwapIn();
}

void RunFolderWriter::SwapIn() {
  // From here the partial folder holds a finished run: whatever happens, it is not deleted.
  done_ = true;
  CommitTempDirectory(partial_, final_);
}

void RequireOutsideOutput(const std::string& out_dir, const std::string& input) {
  if (input.empty()) return;
  if (IsSameOrAncestor(fs::path(out_dir), fs::path(input))) {
    throw InputError("output folder " + out_dir + " holds the input " + input +
                     "; a run replaces its folder as a whole: choose another --out");
  }
  std::error_code ec;
  if (fs::is_directory(input, ec) && IsSameOrAncestor(fs::path(input), fs::path(out_dir))) {
    throw InputError("output folder " + out_dir + " lies inside the input folder " + input +
                     ", which the run reads: choose another --out");
  }
}

std::string OutputsLine(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    names.push_back(e.path().filename().string() + (e.is_directory(ec) ? "/" : ""));
  }
  std::sort(names.begin(), names.end());
  std::string line = dir + "/{";
  for (size_t i = 0; i < names.size(); ++i) line += (i ? "," : "") + names[i];
  return line + "}";
}

bool LooksLikeRunFolder(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(fs::path(dir) / kRunCompleteMarker, ec) || fs::exists(fs::path(dir) / kRunIncompleteMarker, ec)) return true;
  // A run written before markers existed: its metrics beside its resolved inputs.
  const fs::path d(dir);
  if (fs::exists(d / "metrics.json", ec) && (fs::exists(d / "scenario.yaml", ec) || fs::exists(d / "slam_settings.yaml", ec))) {
    return true;
  }
  return d.filename().string().find(kPartialInfix) != std::string::npos;
}

bool IsCompleteRunFolder(const std::string& dir, std::string* why) {
  auto fail = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  std::error_code ec;
  const fs::path root(dir);
  if (fs::exists(root / kRunIncompleteMarker, ec)) {
    std::string reason = "interrupted";
    try {
      const YAML::Node m = LoadRunJsonFile((root / kRunIncompleteMarker).string());
      if (m["reason"]) reason = "interrupted: " + m["reason"].as<std::string>();
    } catch (const std::exception&) {
      reason = "interrupted (its marker is unreadable)";
    }
    return fail(reason);
  }
  if (!fs::exists(root / kRunCompleteMarker, ec)) {
    return fail("no completion marker " + std::string(kRunCompleteMarker) +
                " (the run was killed, is still running, or was written by an older viqu)");
  }
  try {
    const YAML::Node m = LoadRunJsonFile((root / kRunCompleteMarker).string());
    if (!m["files"] || !m["files"].IsSequence()) return fail(std::string(kRunCompleteMarker) + " lists no files");
    for (const YAML::Node& f : m["files"]) {
      const std::string path = f["path"].as<std::string>();
      const uintmax_t bytes = f["bytes"].as<uintmax_t>();
      const fs::path p = root / path;
      if (!fs::is_regular_file(p, ec)) return fail(path + " is missing (listed in " + kRunCompleteMarker + ")");
      if (fs::file_size(p, ec) != bytes) {
        return fail(path + " has changed since the run (" + std::to_string(fs::file_size(p, ec)) + " bytes, " +
                    kRunCompleteMarker + " says " + std::to_string(bytes) + ")");
      }
    }
  } catch (const std::exception& e) {
    return fail(std::string(kRunCompleteMarker) + " is unreadable: " + e.what());
  }
  return true;
}

void RequireCompleteRunFolder(const std::string& dir) {
  std::string why;
  if (!IsCompleteRunFolder(dir, &why)) throw InputError(dir + ": not a complete run folder: " + why);
}

void RequireNotInIncompleteRun(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(path, ec).lexically_normal();
  if (!fs::is_directory(p, ec)) p = p.parent_path();
  for (int up = 0; up < 2 && !p.empty(); ++up, p = p.parent_path()) {
    if (!LooksLikeRunFolder(p.string())) continue;
    std::string why;
    if (!IsCompleteRunFolder(p.string(), &why)) {
      throw InputError(path + ": lies in the run folder " + p.string() + ", which is incomplete or was changed after the run: " + why);
    }
    return;
  }
}

}  // namespace viqu

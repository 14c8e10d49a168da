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

namespace viqu {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPartialInfix = ".partial-";
constexpr int kMarkerFormat = 1;  // version of the markers' layout

// Files a viqu run writes at its top level before markers existed: a folder holding one of them
// is a run folder of ours (an older one), so replacing it destroys nothing of the user's.
const char* const kRunFiles[] = {"scenario.yaml", "metrics.json", "slam_settings.yaml", "trajectory_gt.txt",
                                 "trajectory_est.txt"};

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

// Removes DIR.partial-PID folders left by runs whose process no longer exists (killed runs).
void RemoveStalePartials(const fs::path& final_dir) {
  std::error_code ec;
  const fs::path parent = final_dir.parent_path().empty() ? fs::path(".") : final_dir.parent_path();
  const std::string prefix = final_dir.filename().string() + kPartialInfix;
  for (const fs::directory_entry& e : fs::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string pid_text = name.substr(prefix.size());
    if (pid_text.empty() || !std::all_of(pid_text.begin(), pid_text.end(), ::isdigit)) continue;
    if (ProcessAlive(std::stol(pid_text))) continue;
    std::error_code rm;
    fs::remove_all(e.path(), rm);
  }
}

// Whether `a` is `b` or a folder above it.
bool IsSameOrAncestor(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  const fs::path ca = fs::weakly_canonical(a, ec);
  const fs::path cb = fs::weakly_canonical(b, ec);
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

RunFolderWriter::RunFolderWriter(const std::string& final_dir, bool force, const std::string& command_line)
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
  if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec) && !LooksLikeRunFolder(final_) && !force) {
    throw InputError("output folder " + final_ +
                     " is not empty and holds no viqu run; a run replaces its folder as a whole: choose another --out "
                     "or pass --force");
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
  CommitTempDirectory(partial_, final_);
  done_ = true;
}

bool LooksLikeRunFolder(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(fs::path(dir) / kRunCompleteMarker, ec) || fs::exists(fs::path(dir) / kRunIncompleteMarker, ec)) return true;
  for (const char* f : kRunFiles) {
    if (fs::exists(fs::path(dir) / f, ec)) return true;
  }
  return fs::path(dir).filename().string().find(kPartialInfix) != std::string::npos;
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
      const YAML::Node m = YAML::LoadFile((root / kRunIncompleteMarker).string());
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
    const YAML::Node m = YAML::LoadFile((root / kRunCompleteMarker).string());
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
      throw InputError(path + ": lies in an incomplete run folder " + p.string() + ": " + why);
    }
    return;
  }
}

}  // namespace viqu

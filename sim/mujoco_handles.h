#pragma once
// RAII ownership of MuJoCo's model and data, and an error handler that throws instead of exiting.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace viqu::sim {

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using DataPtr = std::unique_ptr<mjData, MjDataDeleter>;

// Installs (once, process wide) handlers so that mju_error throws viqu::RunError and
// mju_warning messages are collected (see TakeMujocoWarnings) instead of printed.
void InstallMujocoHandlers();

// Warnings MuJoCo emitted since the last call; clears the list.
std::vector<std::string> TakeMujocoWarnings();

// Loads an MJCF file; throws viqu::InputError naming the file and MuJoCo's message on failure.
ModelPtr LoadModelFile(const std::string& path);

// Loads MJCF text (written to a temporary file next to nothing: paths in it must be
// absolute-resolvable, see scene_composer.h). Throws viqu::InputError on failure naming `what`;
// with `source_of_line` ("FILE:LINE" that line N of `xml` came from, "" when none, e.g.
// SourceOfComposedLine) an error MuJoCo reports at a line of `xml` names that file and line.
ModelPtr LoadModelString(const std::string& xml, const std::string& what,
                         const std::function<std::string(int)>& source_of_line = {});

// Name of object `id` of type `type`, or "" if unnamed.
std::string MjName(const mjModel* m, mjtObj type, int id);

// Id of a named object; throws viqu::InputError if absent (`what` names the model).
int MjIdOrThrow(const mjModel* m, mjtObj type, const std::string& name, const std::string& what);

}  // namespace viqu::sim

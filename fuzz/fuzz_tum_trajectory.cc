// libFuzzer target: the TUM trajectory reader (slam/eval/trajectory.h), and ATE/RPE of what it
// accepts against itself (what `viqu eval` does with two files).
#include "common/errors.h"
#include "fuzz/fuzz_input_file.h"
#include "slam/eval/trajectory.h"
#include "slam/eval/trajectory_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = viqu::fuzz::WriteInput("traj.txt", data, size);
  try {
    const viqu::eval::Trajectory t = viqu::eval::ReadTumTrajectory(path);
    viqu::eval::ComputeAte(t, t);
    viqu::eval::ComputeRpe(t, t, 1);
  } catch (const viqu::InputError&) {
  }
  return 0;
}

// libFuzzer target: the SLAM settings loader (slam/settings/slam_settings.h) on arbitrary bytes.
#include "common/errors.h"
#include "fuzz/fuzz_input_file.h"
#include "slam/settings/slam_settings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = viqu::fuzz::WriteInput("slam.yaml", data, size);
  try {
    viqu::slam::LoadSlamSettings(path);
  } catch (const viqu::InputError&) {
  }
  return 0;
}

// libFuzzer target: the scenario loader (scenario/scenario_loader.h) on arbitrary bytes. The
// scenario sits where the shipped ones do relative to models/ and assets/ (symlinks), so that
// mutations of the corpus (the shipped scenarios) reach past the file-existence checks.
#include <filesystem>

#include "common/errors.h"
#include "fuzz/fuzz_input_file.h"
#include "scenario/scenario_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const bool linked = [] {
    std::error_code ec;
    for (const char* d : {"models", "assets"}) fs::create_directory_symlink(fs::path(VIQU_SOURCE_DIR) / d, viqu::fuzz::WorkDir() / d, ec);
    return true;
  }();
  (void)linked;
  const std::string path = viqu::fuzz::WriteInput("scenarios/s.yaml", data, size);
  try {
    viqu::LoadScenario(path, {});
  } catch (const viqu::InputError&) {
  }
  return 0;
}

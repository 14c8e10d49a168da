#pragma once
// libFuzzer helpers: the readers under test take file paths, so each input is written to a file
// in a per-process temporary folder first. Expected failures are InputError (bad input, exit 2);
// anything else escaping a reader is a bug, and libFuzzer reports it as a crash.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace viqu::fuzz {

// A folder of this process's own under the temporary folder (created once).
inline const std::filesystem::path& WorkDir() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("viqu_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// Writes the fuzzer's bytes to WorkDir()/name and returns the path.
inline std::string WriteInput(const std::string& name, const uint8_t* data, size_t size) {
  const std::filesystem::path p = WorkDir() / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return p.string();
}

}  // namespace viqu::fuzz

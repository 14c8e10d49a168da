#pragma once
// The whole of a file as bytes ("" when it cannot be read): for tests that compare outputs.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace viqu::testing {

inline std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace viqu::testing

#pragma once
// Scenario files written by tests that drive the program: the shipped static_room with lines
// appended, its relative model and asset paths made absolute so that it can live elsewhere.
// Header-only, shared by test_bad_input and test_hostile_input.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace viqu::testing {

inline void WriteText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

inline std::string ReadText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// DIR/NAME: scenarios/static_room.yaml with `extra` appended.
inline std::string ScenarioWith(const std::filesystem::path& dir, const std::string& name, const std::string& extra) {
  const std::string source = VIQU_SOURCE_DIR;
  std::string text = ReadText(source + "/scenarios/static_room.yaml");
  for (size_t at; (at = text.find("../models")) != std::string::npos;) text.replace(at, 9, source + "/models");
  for (size_t at; (at = text.find("../assets")) != std::string::npos;) text.replace(at, 9, source + "/assets");
  const std::filesystem::path p = dir / name;
  WriteText(p, text + extra);
  return p.string();
}

}  // namespace viqu::testing

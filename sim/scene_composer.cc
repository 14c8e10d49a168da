#include "sim/scene_composer.h"

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/errors.h"
#include "common/input_file.h"

namespace viqu::sim {
namespace {

// The largest MJCF piece read (bytes): the shipped worlds are a few KiB; meshes and textures are
// separate files that MuJoCo reads.
constexpr uintmax_t kMaxMjcfFileBytes = uintmax_t{16} << 20;

std::string ReadText(const std::string& path) { return ReadInputFile(path, kMaxMjcfFileBytes, "MJCF file"); }

std::string Folder(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// Removes <!-- ... --> so that commented-out markup does not confuse the checks below; a
// comment's line breaks stay, so that the text keeps the file's line numbers.
std::string StripComments(const std::string& xml) {
  std::string out;
  out.reserve(xml.size());
  size_t pos = 0;
  while (true) {
    const size_t open = xml.find("<!--", pos);
    if (open == std::string::npos) break;
    const size_t close = xml.find("-->", open + 4);
    out.append(xml, pos, open - pos);
    const size_t end = close == std::string::npos ? xml.size() : close + 3;
    out.append(static_cast<size_t>(std::count(xml.begin() + static_cast<std::ptrdiff_t>(open),
                                              xml.begin() + static_cast<std::ptrdiff_t>(end), '\n')),
               '\n');
    pos = end;
  }
  out.append(xml, pos, std::string::npos);
  return out;
}

constexpr const char* kPieceMarker = "<!-- viqu piece: ";

}  // namespace

std::string InlineMjcfPiece(const std::string& path, int* first_line) {
  const std::string xml = StripComments(ReadText(path));
  const auto open = xml.find("<mujoco");
  const auto open_end = open == std::string::npos ? open : xml.find('>', open);
  const auto close = xml.rfind("</mujoco>");
  if (open == std::string::npos || open_end == std::string::npos || close == std::string::npos ||
      close < open_end) {
    throw InputError(path + ": not an MJCF file (no <mujoco> ... </mujoco> root)");
  }
  std::string inner = xml.substr(open_end + 1, close - open_end - 1);
  if (first_line) *first_line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + static_cast<std::ptrdiff_t>(open_end), '\n'));
  if (inner.find("<compiler") != std::string::npos || inner.find("<include") != std::string::npos) {
    throw InputError(path + ": MJCF pieces must not contain <compiler> or <include> (the scene "
                            "composer writes the header)");
  }
  static const std::regex kFile("file=\"([^\"/][^\"]*)\"");
  return std::regex_replace(inner, kFile, "file=\"" + Folder(path) + "/$1\"");
}

std::string ComposeSceneXml(const Scenario& s, const SceneHeader& h,
                            const std::vector<std::string>& generated) {
  // The camera clipping planes are the renderer's (RenderOptions::z_near_m / z_far_m).
  std::ostringstream x;
  x.precision(9);
  x << "<mujoco model=\"viqu:" << s.name << "\">\n"
    << "  <compiler angle=\"degree\" inertiafromgeom=\"auto\"/>\n"
    << "  <option timestep=\"" << h.timestep_s << "\" gravity=\"0 0 -9.81\" cone=\"" << h.cone
    << "\" impratio=\"" << h.impratio << "\" noslip_iterations=\"" << h.noslip_iterations << "\"/>\n"
    << "  <size nconmax=\"400\" njmax=\"1500\"/>\n"
    << "  <visual>\n"
    << "    <global offwidth=\"" << h.offscreen_width << "\" offheight=\"" << h.offscreen_height << "\"/>\n"
    << "    <quality shadowsize=\"0\"/>\n"
    << "  </visual>\n"
    ;
  // Each piece's marker names its file and the line its text starts on, so that an error MuJoCo
  // reports at a line of the composed scene can name the piece's own file and line
  // (SourceOfComposedLine). The marker and the text start on the same line.
  for (const std::string& path : {s.world, s.robot.model}) {
    int first_line = 1;
    const std::string inner = InlineMjcfPiece(path, &first_line);
    x << kPieceMarker << path << " line " << first_line << " -->" << inner << "\n";
  }
  x << kPieceMarker << "(generated) -->\n";
  for (const std::string& piece : generated) x << piece << "\n";
  x << "</mujoco>\n";
  return x.str();
}

std::string SourceOfComposedLine(const std::string& xml, int line) {
  // The last marker at or before `line`: count lines up to each marker.
  std::string source;
  size_t pos = 0;
  int marker_line = 1;
  size_t counted = 0;
  while ((pos = xml.find(kPieceMarker, pos)) != std::string::npos) {
    marker_line += static_cast<int>(std::count(xml.begin() + static_cast<std::ptrdiff_t>(counted),
                                               xml.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
    counted = pos;
    if (marker_line > line) break;
    const size_t text = pos + std::string(kPieceMarker).size();
    const size_t end = xml.find(" -->", text);
    const std::string label = xml.substr(text, end - text);
    const size_t at = label.rfind(" line ");
    source = at == std::string::npos ? std::string()
                                     : label.substr(0, at) + ":" +
                                           std::to_string(std::stoi(label.substr(at + 6)) + line - marker_line);
    pos = end;
  }
  return source;
}

}  // namespace viqu::sim

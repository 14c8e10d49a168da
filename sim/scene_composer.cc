#include "sim/scene_composer.h"

#include <fstream>
#include <regex>
#include <sstream>

#include "common/errors.h"

namespace viqu::sim {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read MJCF file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string Folder(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// Removes <!-- ... --> so that commented-out markup does not confuse the checks below.
std::string StripComments(const std::string& xml) {
  static const std::regex kComment("<!--[\\s\\S]*?-->");
  return std::regex_replace(xml, kComment, "");
}

}  // namespace

std::string InlineMjcfPiece(const std::string& path) {
  const std::string xml = StripComments(ReadText(path));
  const auto open = xml.find("<mujoco");
  const auto open_end = open == std::string::npos ? open : xml.find('>', open);
  const auto close = xml.rfind("</mujoco>");
  if (open == std::string::npos || open_end == std::string::npos || close == std::string::npos ||
      close < open_end) {
    throw InputError(path + ": not an MJCF file (no <mujoco> ... </mujoco> root)");
  }
  std::string inner = xml.substr(open_end + 1, close - open_end - 1);
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
    << "  <!-- world: " << s.world << " -->\n"
    << InlineMjcfPiece(s.world) << "\n"
    << "  <!-- robot: " << s.robot.model << " -->\n"
    << InlineMjcfPiece(s.robot.model) << "\n";
  for (const std::string& piece : generated) x << piece << "\n";
  x << "</mujoco>\n";
  return x.str();
}

}  // namespace viqu::sim

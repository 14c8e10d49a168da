#include "sim/terrain.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "common/errors.h"
#include "sim/mujoco_handles.h"

namespace viqu::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Num(double v) {
  std::ostringstream s;
  s.precision(8);
  s << v;
  return s.str();
}

void Require(bool ok, const std::string& what) {
  if (!ok) throw InputError("terrain: " + what);
}

std::string FrictionAttr(double mu) { return Num(mu) + " 0.005 0.0001"; }

}  // namespace

std::string TerrainXml(const TerrainConfig& terrain) {
  if (terrain.patches.empty() && terrain.slopes.empty()) return {};
  Require(terrain.friction > 0, "friction must be > 0, got " + Num(terrain.friction));
  const std::string dir = std::string(VIQU_SOURCE_DIR) + "/assets/";
  std::ostringstream x;
  x << "<asset>\n"
    << "  <texture name=\"viqu_terrain_tile\" type=\"2d\" file=\"" << dir << "dark_tile.png\"/>\n"
    << "  <material name=\"viqu_terrain_tile\" texture=\"viqu_terrain_tile\" texrepeat=\"2 2\""
       " texuniform=\"true\" specular=\"0.8\" shininess=\"0.9\" reflectance=\"0\"/>\n"
    << "  <texture name=\"viqu_terrain_ramp\" type=\"2d\" file=\"" << dir
    << "floor_terrazzo.png\"/>\n"
    << "  <material name=\"viqu_terrain_ramp\" texture=\"viqu_terrain_ramp\" texrepeat=\"1.2 1.2\""
       " texuniform=\"true\"/>\n"
    << "</asset>\n<worldbody>\n";
  for (size_t i = 0; i < terrain.patches.size(); ++i) {
    const FrictionPatch& p = terrain.patches[i];
    const std::string n = "terrain.patches[" + std::to_string(i) + "]";
    Require(p.size[0] > 0 && p.size[1] > 0, n + ".size must be > 0");
    Require(p.friction > 0, n + ".friction must be > 0, got " + Num(p.friction));
    x << "  <geom name=\"terrain_patch_" << i << "\" type=\"box\" size=\"" << Num(0.5 * p.size[0])
      << " " << Num(0.5 * p.size[1]) << " " << Num(0.5 * kPatchThickness_m) << "\" pos=\""
      << Num(p.center[0]) << " " << Num(p.center[1]) << " "
      << Num(kPatchTop_m - 0.5 * kPatchThickness_m) << "\" friction=\""
      << FrictionAttr(p.friction) << "\" material=\"viqu_terrain_tile\"/>\n";
  }
  for (size_t i = 0; i < terrain.slopes.size(); ++i) {
    const Slope& s = terrain.slopes[i];
    const std::string n = "terrain.slopes[" + std::to_string(i) + "]";
    Require(s.size[0] > 0 && s.size[1] > 0, n + ".size must be > 0");
    Require(s.angle_deg != 0 && std::abs(s.angle_deg) <= 30,
            n + ".angle_deg must be in [-30, 30] and not 0, got " + Num(s.angle_deg));
    // A negative angle descends along yaw_deg: the same ramp, rising the other way.
    const double a = std::abs(s.angle_deg) * kPi / 180.0;
    const double yaw = (s.yaw_deg + (s.angle_deg < 0 ? 180.0 : 0.0)) * kPi / 180.0;
    const double len = s.size[0];
    const Eigen::Vector3d dir(std::cos(yaw), std::sin(yaw), 0);
    // Top surface: starts at floor level at the low end and rises along dir; its horizontal
    // footprint is centred on `center`. The box hangs below it, mostly under the floor.
    const Eigen::Vector3d top_centre = Eigen::Vector3d(s.center[0], s.center[1], 0) +
                                       Eigen::Vector3d(0, 0, 0.5 * len * std::sin(a));
    const Eigen::Vector3d normal = -std::sin(a) * dir + std::cos(a) * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d centre = top_centre - 0.5 * kSlopeThickness_m * normal;
    const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(-a, Eigen::Vector3d::UnitY());
    x << "  <geom name=\"terrain_slope_" << i << "\" type=\"box\" size=\"" << Num(0.5 * len) << " "
      << Num(0.5 * s.size[1]) << " " << Num(0.5 * kSlopeThickness_m) << "\" pos=\""
      << Num(centre.x()) << " " << Num(centre.y()) << " " << Num(centre.z()) << "\" quat=\""
      << Num(q.w()) << " " << Num(q.x()) << " " << Num(q.y()) << " " << Num(q.z())
      << "\" friction=\"" << FrictionAttr(terrain.friction) << "\" material=\"viqu_terrain_ramp\"/>\n";
  }
  x << "</worldbody>\n";
  return x.str();
}

void ApplyFloorFriction(mjModel* m, double friction, const std::string& world_file) {
  if (!(friction > 0)) throw InputError("terrain.friction must be > 0, got " + Num(friction));
  if (mj_name2id(m, mjOBJ_GEOM, "floor") < 0) {
    throw InputError(world_file + ": the world has no geom named 'floor' (the ground the robot walks on and the "
                     "terrain's friction applies to)");
  }
  const int id = MjIdOrThrow(m, mjOBJ_GEOM, "floor", world_file);
  m->geom_friction[3 * id] = friction;
}

std::optional<FloorExtent> FloorExtentOf(const mjModel* m) {
  const int id = mj_name2id(m, mjOBJ_GEOM, "floor");
  if (id < 0 || m->geom_type[id] != mjGEOM_PLANE) return std::nullopt;
  const double hx = m->geom_size[3 * id], hy = m->geom_size[3 * id + 1];
  if (!(hx > 0 && hy > 0)) return std::nullopt;  // size 0: an infinite plane
  // The plane's half-sizes along its own axes, its frame (in the world body) turned about the
  // vertical only: the box around it.
  const double* q = m->geom_quat + 4 * id;  // w x y z
  const double yaw = std::atan2(2 * (q[0] * q[3] + q[1] * q[2]), 1 - 2 * (q[2] * q[2] + q[3] * q[3]));
  const double c = std::abs(std::cos(yaw)), sn = std::abs(std::sin(yaw));
  const double ex = c * hx + sn * hy, ey = sn * hx + c * hy;
  const double* pos = m->geom_pos + 3 * id;
  return FloorExtent{pos[0] - ex, pos[0] + ex, pos[1] - ey, pos[1] + ey};
}

}  // namespace viqu::sim

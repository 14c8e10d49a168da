#pragma once
// Terrain of a scenario: low-friction patches and slopes as MJCF geoms.
//
// MuJoCo mixes the friction of two touching geoms by taking the larger, so the robot's feet
// carry a very low friction and the ground sets the friction the feet feel: the floor gets
// terrain.friction (ApplyFloorFriction), and every patch is a thin textured box whose top surface
// lies kPatchTop_m above the floor, so that a foot on it touches the patch only.
#include <optional>
#include <string>

#include <mujoco/mujoco.h>

#include "scenario/scenario.h"

namespace viqu::sim {

constexpr double kPatchTop_m = 0.0015;        // height of a patch's top surface above the floor (m)
constexpr double kPatchThickness_m = 0.006;   // full thickness of a patch box (m)
constexpr double kSlopeThickness_m = 0.2;     // thickness of a slope box, mostly under the floor (m)

// MJCF text (an <asset> and a <worldbody> section) with geoms `terrain_patch_N` (thin boxes with
// the patch's friction) and `terrain_slope_N` (tilted boxes whose top surface starts at floor
// level at the low end and rises at angle_deg along yaw_deg; a negative angle descends along
// yaw_deg, i.e. rises the opposite way). Empty when there is no patch and
// no slope. Throws viqu::InputError on out-of-range values.
std::string TerrainXml(const TerrainConfig& terrain);

// Sets the sliding friction of the geom named `floor`; throws viqu::InputError if it is absent
// or the friction is not positive.
void ApplyFloorFriction(mjModel* m, double friction, const std::string& world_file = "world");

// The world's floor (the plane geom 'floor') in the ground plane: x in [x_min, x_max], y in
// [y_min, y_max] (m). nullopt when there is no floor or it is an unbounded plane (size 0).
struct FloorExtent {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
  bool Holds(const Vec2& p) const { return p[0] >= x_min && p[0] <= x_max && p[1] >= y_min && p[1] <= y_max; }
};
std::optional<FloorExtent> FloorExtentOf(const mjModel* m);

}  // namespace viqu::sim

#pragma once
// Semantic instance of every body of a composed MuJoCo scene (docs/CONVENTIONS.md).
#include <cstdint>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {

// Maps every body to the instance of its root body (a child of the world body):
//  - the world body and unprefixed root bodies: static background, instance 0;
//  - the subtree of the root body `trunk`: the robot (Category::kRobot, name "trunk");
//  - root bodies named `CATEGORY:INSTANCE[/PART]`, CATEGORY one of person, box, ball,
//    furniture: all parts with the same `CATEGORY:INSTANCE` form one instance named INSTANCE.
// Ids 1, 2, ... follow the order of the first body of each instance, so they are fixed for a
// model. Computed once per model.
class SegmentationIds {
 public:
  // Throws viqu::InputError for a root body `X:Y` whose category X is unknown or whose instance
  // Y is empty, and if a model has more than 65535 instances.
  explicit SegmentationIds(const mjModel* m);

  // Instance id of body `body_id` (0 = background).
  uint16_t OfBody(int body_id) const { return body_instance_[static_cast<size_t>(body_id)]; }

  // Instance id of a rendered object (mjvGeom objtype/objid); decor and non-geom objects are 0.
  uint16_t OfObject(const mjModel* m, int objtype, int objid) const;

  // Description of instance `id`, for 0 <= id < size().
  const SegmentInstance& Instance(uint16_t id) const { return instances_[id]; }

  // Number of instances including the background.
  size_t size() const { return instances_.size(); }

 private:
  std::vector<uint16_t> body_instance_;     // instance id per body (nbody)
  std::vector<SegmentInstance> instances_;  // [id]; [0] is the background
};

// Category of a CONVENTIONS category word ("person", ...); false if the word is not one.
bool ParseCategory(const std::string& word, Category* category);

}  // namespace viqu::sim

#include "sim/segmentation_ids.h"

#include <limits>
#include <map>

#include "common/errors.h"
#include "sim/mujoco_handles.h"

namespace viqu::sim {
namespace {

constexpr const char* kRobotRootBody = "trunk";

}  // namespace

bool ParseCategory(const std::string& word, Category* category) {
  static const std::map<std::string, Category> kWords = {{"person", Category::kPerson},
                                                         {"box", Category::kBox},
                                                         {"ball", Category::kBall},
                                                         {"furniture", Category::kFurniture}};
  const auto it = kWords.find(word);
  if (it == kWords.end()) return false;
  *category = it->second;
  return true;
}

SegmentationIds::SegmentationIds(const mjModel* m) {
  instances_.push_back(SegmentInstance{0, Category::kBackground, "background"});
  body_instance_.assign(static_cast<size_t>(m->nbody), 0);

  std::map<std::string, uint16_t> id_of_key;  // "CATEGORY:INSTANCE" (or "trunk") -> id
  for (int b = 1; b < m->nbody; ++b) {
    const int root = m->body_rootid[b];
    if (root != b) {
      // Children come after their parents in MuJoCo's body order.
      body_instance_[static_cast<size_t>(b)] = body_instance_[static_cast<size_t>(root)];
      continue;
    }
    const std::string name = MjName(m, mjOBJ_BODY, b);
    std::string key, instance_name;
    Category category = Category::kBackground;
    if (name == kRobotRootBody) {
      key = instance_name = name;
      category = Category::kRobot;
    } else {
      const size_t colon = name.find(':');
      if (colon == std::string::npos) continue;  // unprefixed: static background
      const std::string word = name.substr(0, colon);
      const size_t slash = name.find('/', colon + 1);
      instance_name = name.substr(colon + 1, slash == std::string::npos ? std::string::npos : slash - colon - 1);
      if (!ParseCategory(word, &category) || instance_name.empty()) {
        throw InputError("MuJoCo body '" + name +
                         "': a root body with ':' in its name must be CATEGORY:INSTANCE[/PART] with "
                         "CATEGORY one of person, box, ball, furniture");
      }
      key = word + ":" + instance_name;
    }
    auto it = id_of_key.find(key);
    if (it == id_of_key.end()) {
      if (instances_.size() > std::numeric_limits<uint16_t>::max()) {
        throw InputError("MuJoCo model has more than 65535 segmentation instances");
      }
      const auto id = static_cast<uint16_t>(instances_.size());
      instances_.push_back(SegmentInstance{id, category, instance_name});
      it = id_of_key.emplace(key, id).first;
    }
    body_instance_[static_cast<size_t>(b)] = it->second;
  }
}

uint16_t SegmentationIds::OfObject(const mjModel* m, int objtype, int objid) const {
  if (objid < 0) return 0;
  switch (objtype) {
    case mjOBJ_GEOM: return OfBody(m->geom_bodyid[objid]);
    case mjOBJ_SITE: return OfBody(m->site_bodyid[objid]);
    case mjOBJ_BODY:
    case mjOBJ_XBODY: return OfBody(objid);
    default: return 0;
  }
}

}  // namespace viqu::sim

#include "sim/obstacles.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/errors.h"
#include "sim/mujoco_handles.h"

namespace viqu::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Obstacles float this far above the floor: mocap bodies are kinematic, and a resting contact
// with the floor would only cost collision time (m).
constexpr double kLift_m = 0.002;
// Person proportions for a 1.70 m figure, scaled by height / 1.70 (m).
constexpr double kRefHeight_m = 1.70;
constexpr double kHipZ = 0.90;        // leg pivot height
constexpr double kHipY = 0.09;        // leg pivot lateral offset
constexpr double kLegLength = 0.885;  // pivot to sole: soles 1.5 cm above the floor
constexpr double kStride = 1.40;      // distance walked per full gait cycle (two steps)
constexpr double kSwingRad = 0.35;    // leg swing amplitude (rad)

std::string Where(const ObstacleConfig& c) { return "obstacle '" + c.name + "'"; }

void Validate(const ObstacleConfig& c) {
  if (c.name.empty()) throw InputError("obstacle: empty name");
  if (c.name.find_first_of(":/ \"<>&") != std::string::npos)
    throw InputError(Where(c) + ": name must not contain ':', '/', spaces or XML characters");
  const std::string& k = c.category;
  if (k != "person" && k != "box" && k != "ball" && k != "furniture")
    throw InputError(Where(c) + ": category '" + k + "', expected person | box | ball | furniture");
  if (c.path.empty()) throw InputError(Where(c) + ": path needs at least one point");
  if (c.loop != "none" && c.loop != "loop" && c.loop != "pingpong")
    throw InputError(Where(c) + ": loop '" + c.loop + "', expected none | loop | pingpong");
  if (c.path.size() > 1 && !(c.speed_mps > 0))
    throw InputError(Where(c) + ": speed_mps must be > 0, got " + std::to_string(c.speed_mps));
  if (!(c.pause_s >= 0)) throw InputError(Where(c) + ": pause_s must be >= 0");
  for (double s : c.size_m)
    if (!(s > 0)) throw InputError(Where(c) + ": size_m values must be > 0");
  const size_t n = c.size_m.size();
  if ((k == "box" || k == "furniture") && n != 0 && n != 3)
    throw InputError(Where(c) + ": size_m of a " + k + " is [x, y, z]");
  if ((k == "ball" || k == "person") && n > 1)
    throw InputError(Where(c) + ": size_m of a " + k + " has one value");
  if (k == "person" && n == 1 && (c.size_m[0] < 0.5 || c.size_m[0] > 2.5))
    throw InputError(Where(c) + ": person height must be within [0.5, 2.5] m");
}

Eigen::Vector3d BoxSize(const ObstacleConfig& c) {
  if (c.size_m.size() == 3) return {c.size_m[0], c.size_m[1], c.size_m[2]};
  return c.category == "furniture" ? Eigen::Vector3d(0.6, 0.4, 0.8) : Eigen::Vector3d(0.3, 0.3, 0.3);
}
double BallDiameter(const ObstacleConfig& c) { return c.size_m.empty() ? 0.2 : c.size_m[0]; }
double PersonScale(const ObstacleConfig& c) {
  return (c.size_m.empty() ? 1.72 : c.size_m[0]) / kRefHeight_m;
}

Eigen::Quaterniond YawQuat(double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

}  // namespace

// ------------------------------------------------------------------------------ ObstaclePath
ObstaclePath::ObstaclePath(const ObstacleConfig& cfg) {
  Validate(cfg);
  start_w_ = {cfg.path[0][0], cfg.path[0][1]};
  start_s_ = cfg.start_s;
  yaw0_rad_ = cfg.yaw_deg * kPi / 180.0;
  repeats_ = cfg.loop != "none";
  const size_t n = cfg.path.size();
  if (n < 2) return;  // never moves

  std::vector<Eigen::Vector2d> seq;
  for (const Vec2& p : cfg.path) seq.emplace_back(p[0], p[1]);
  if (cfg.loop == "loop") {
    seq.push_back(seq.front());
  } else if (cfg.loop == "pingpong") {
    for (size_t i = n - 1; i-- > 0;) seq.emplace_back(cfg.path[i][0], cfg.path[i][1]);
  }
  double t = 0, dist = 0, yaw = yaw0_rad_;
  bool have_yaw = false;
  for (size_t i = 0; i + 1 < seq.size(); ++i) {
    Leg leg;
    leg.from_w = seq[i];
    leg.to_w = seq[i + 1];
    leg.length_m = (leg.to_w - leg.from_w).norm();
    leg.walk_s = leg.length_m / cfg.speed_mps;
    leg.pause_s = cfg.pause_s;
    leg.begin_s = t;
    leg.distance_before_m = dist;
    if (leg.length_m > 0) {
      const Eigen::Vector2d d = leg.to_w - leg.from_w;
      yaw = std::atan2(d.y(), d.x());
      if (!have_yaw) {  // zero-length legs before the first real one take its heading
        for (Leg& l : legs_) l.yaw_rad = yaw;
        have_yaw = true;
      }
    }
    leg.yaw_rad = yaw;
    t += leg.walk_s + leg.pause_s;
    dist += leg.length_m;
    legs_.push_back(leg);
  }
  cycle_s_ = t;
  cycle_m_ = dist;
  if (cycle_m_ <= 0) legs_.clear();  // all points equal: never moves
}

ObstaclePath::Where ObstaclePath::Locate(double t) const {
  Where w;
  const double tau = t - start_s_;
  if (legs_.empty() || tau < 0) return w;
  w.before_start = false;
  double r = tau;
  if (repeats_) {
    w.cycle = static_cast<long>(std::floor(tau / cycle_s_));
    r = tau - static_cast<double>(w.cycle) * cycle_s_;
  } else if (tau >= legs_.back().begin_s + legs_.back().walk_s) {
    w.finished = true;
    w.leg = static_cast<int>(legs_.size()) - 1;
    w.fraction = 1;
    return w;
  }
  // The leg whose [begin, begin + walk + pause) holds r; the last one takes any rounding excess.
  int i = static_cast<int>(legs_.size()) - 1;
  for (int k = 0; k + 1 < static_cast<int>(legs_.size()); ++k) {
    if (r < legs_[k + 1].begin_s) {
      i = k;
      break;
    }
  }
  const Leg& leg = legs_[i];
  const double into = std::max(0.0, r - leg.begin_s);
  w.leg = i;
  w.moving = into < leg.walk_s;
  w.fraction = leg.walk_s > 0 ? std::min(1.0, into / leg.walk_s) : 1.0;
  return w;
}

Eigen::Vector2d ObstaclePath::Position(double t) const {
  const Where w = Locate(t);
  if (w.leg < 0) return start_w_;
  const Leg& leg = legs_[w.leg];
  return leg.from_w + w.fraction * (leg.to_w - leg.from_w);
}

double ObstaclePath::Yaw(double t) const {
  const Where w = Locate(t);
  return w.leg < 0 ? yaw0_rad_ : legs_[w.leg].yaw_rad;
}

bool ObstaclePath::Moving(double t) const { return Locate(t).moving; }

double ObstaclePath::Distance(double t) const {
  const Where w = Locate(t);
  if (w.leg < 0) return 0;
  const Leg& leg = legs_[w.leg];
  return static_cast<double>(w.cycle) * cycle_m_ + leg.distance_before_m + w.fraction * leg.length_m;
}

// ------------------------------------------------------------------------------ ObstaclesXml
namespace {

std::string Num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}
std::string V3(double a, double b, double c) { return Num(a) + " " + Num(b) + " " + Num(c); }

std::string QuatAttr(const Eigen::Quaterniond& q) {
  return V3(q.w(), q.x(), q.y()) + " " + Num(q.z());
}

constexpr const char* kGeomClass = R"(contype="1" conaffinity="1" condim="3" friction="0.8 0.005 0.0001")";

std::string AssetXml() {
  const std::string dir = std::string(VIQU_SOURCE_DIR) + "/assets/";
  std::ostringstream x;
  x << "<asset>\n";
  const char* cube[][2] = {{"shirt", "shirt"}, {"trousers", "trousers"}, {"skin", "skin"},
                           {"cardboard", "cardboard"}, {"wood", "wood"}, {"ball", "rug"}};
  for (const auto& c : cube) {
    x << "  <texture name=\"viqu_obst_" << c[0] << "\" type=\"cube\" file=\"" << dir << c[1]
      << ".png\"/>\n";
    x << "  <material name=\"viqu_obst_" << c[0] << "\" texture=\"viqu_obst_" << c[0]
      << "\" specular=\"0.1\" shininess=\"0.1\"/>\n";
  }
  x << "</asset>\n";
  return x.str();
}

void PersonXml(const ObstacleConfig& c, const ObstaclePath& path, std::ostringstream& x) {
  const double s = PersonScale(c);
  const Eigen::Vector2d p = path.Position(0);
  const Eigen::Quaterniond q = YawQuat(path.Yaw(0));
  const std::string base = "person:" + c.name;
  // Torso, head and arms: one rigid body with its origin on the floor under the figure.
  x << "  <body name=\"" << base << "\" mocap=\"true\" pos=\"" << V3(p.x(), p.y(), 0)
    << "\" quat=\"" << QuatAttr(q) << "\">\n";
  x << "    <geom name=\"" << base << "/pelvis\" type=\"box\" size=\"" << V3(0.10 * s, 0.17 * s, 0.06 * s)
    << "\" pos=\"" << V3(0, 0, 0.98 * s) << "\" material=\"viqu_obst_trousers\" " << kGeomClass << "/>\n";
  x << "    <geom name=\"" << base << "/torso\" type=\"box\" size=\"" << V3(0.11 * s, 0.19 * s, 0.25 * s)
    << "\" pos=\"" << V3(0, 0, 1.29 * s) << "\" material=\"viqu_obst_shirt\" " << kGeomClass << "/>\n";
  x << "    <geom name=\"" << base << "/neck\" type=\"capsule\" size=\"" << Num(0.045 * s)
    << "\" fromto=\"" << V3(0, 0, 1.54 * s) << " " << V3(0, 0, 1.58 * s)
    << "\" material=\"viqu_obst_skin\" " << kGeomClass << "/>\n";
  x << "    <geom name=\"" << base << "/head\" type=\"ellipsoid\" size=\"" << V3(0.095 * s, 0.08 * s, 0.11 * s)
    << "\" pos=\"" << V3(0.01 * s, 0, 1.60 * s + 0.08 * s) << "\" material=\"viqu_obst_skin\" "
    << kGeomClass << "/>\n";
  x << "    <geom name=\"" << base << "/hair\" type=\"ellipsoid\" size=\"" << V3(0.09 * s, 0.085 * s, 0.05 * s)
    << "\" pos=\"" << V3(-0.01 * s, 0, 1.73 * s) << "\" rgba=\"0.15 0.1 0.05 1\" " << kGeomClass << "/>\n";
  for (int side : {1, -1}) {
    const double y = side * 0.245 * s;
    x << "    <geom name=\"" << base << (side > 0 ? "/arm_l" : "/arm_r")
      << "\" type=\"capsule\" size=\"" << Num(0.045 * s) << "\" fromto=\""
      << V3(0, y, 1.47 * s) << " " << V3(0.05 * s, y + side * 0.02 * s, 0.88 * s)
      << "\" material=\"viqu_obst_shirt\" " << kGeomClass << "/>\n";
  }
  x << "  </body>\n";
  // Legs: separate mocap bodies pivoting at the hip, so that they swing while walking.
  for (int side : {1, -1}) {
    const Eigen::Vector3d hip = q * Eigen::Vector3d(0, side * kHipY * s, kHipZ * s);
    const std::string name = base + (side > 0 ? "/leg_l" : "/leg_r");
    x << "  <body name=\"" << name << "\" mocap=\"true\" pos=\""
      << V3(p.x() + hip.x(), p.y() + hip.y(), hip.z()) << "\" quat=\"" << QuatAttr(q) << "\">\n";
    // A box leg: a cube texture maps the whole trousers image onto each face (corner-rich).
    x << "    <geom name=\"" << name << "/leg\" type=\"box\" size=\"" << V3(0.065 * s, 0.06 * s, 0.37 * s)
      << "\" pos=\"" << V3(0, 0, -0.45 * s) << "\" material=\"viqu_obst_trousers\" " << kGeomClass
      << "/>\n";
    x << "    <geom name=\"" << name << "/shoe\" type=\"box\" size=\"" << V3(0.12 * s, 0.05 * s, 0.035 * s)
      << "\" pos=\"" << V3(0.05 * s, 0, -(kLegLength - 0.035) * s) << "\" rgba=\"0.12 0.1 0.1 1\" "
      << kGeomClass << "/>\n";
    x << "  </body>\n";
  }
}

void RigidXml(const ObstacleConfig& c, const ObstaclePath& path, std::ostringstream& x) {
  const Eigen::Vector2d p = path.Position(0);
  const std::string name = c.category + ":" + c.name;
  if (c.category == "ball") {
    const double r = 0.5 * BallDiameter(c);
    x << "  <body name=\"" << name << "\" mocap=\"true\" pos=\"" << V3(p.x(), p.y(), r + kLift_m)
      << "\">\n";
    x << "    <geom name=\"" << name << "/ball\" type=\"sphere\" size=\"" << Num(r)
      << "\" material=\"viqu_obst_ball\" " << kGeomClass << "/>\n";
    x << "  </body>\n";
    return;
  }
  const Eigen::Vector3d size = BoxSize(c);
  const Eigen::Quaterniond q = YawQuat(c.yaw_deg * kPi / 180.0);
  x << "  <body name=\"" << name << "\" mocap=\"true\" pos=\""
    << V3(p.x(), p.y(), 0.5 * size.z() + kLift_m) << "\" quat=\"" << QuatAttr(q) << "\">\n";
  if (c.category == "box") {
    x << "    <geom name=\"" << name << "/box\" type=\"box\" size=\""
      << V3(0.5 * size.x(), 0.5 * size.y(), 0.5 * size.z()) << "\" material=\"viqu_obst_cardboard\" "
      << kGeomClass << "/>\n";
  } else {  // furniture: a cabinet on a dark plinth
    const double plinth = std::min(0.06, 0.2 * size.z());
    x << "    <geom name=\"" << name << "/body\" type=\"box\" size=\""
      << V3(0.5 * size.x(), 0.5 * size.y(), 0.5 * (size.z() - plinth)) << "\" pos=\""
      << V3(0, 0, 0.5 * plinth) << "\" material=\"viqu_obst_wood\" " << kGeomClass << "/>\n";
    x << "    <geom name=\"" << name << "/plinth\" type=\"box\" size=\""
      << V3(0.5 * size.x() - 0.02, 0.5 * size.y() - 0.02, 0.5 * plinth) << "\" pos=\""
      << V3(0, 0, -0.5 * (size.z() - plinth)) << "\" rgba=\"0.1 0.08 0.06 1\" " << kGeomClass << "/>\n";
  }
  x << "  </body>\n";
}

}  // namespace

std::string ObstaclesXml(const std::vector<ObstacleConfig>& obstacles) {
  if (obstacles.empty()) return {};
  std::ostringstream x;
  x << AssetXml() << "<worldbody>\n";
  std::vector<std::string> names;
  for (const ObstacleConfig& c : obstacles) {
    const ObstaclePath path(c);  // validates
    if (std::find(names.begin(), names.end(), c.name) != names.end())
      throw InputError("obstacle '" + c.name + "': name used twice");
    names.push_back(c.name);
    if (c.category == "person") {
      PersonXml(c, path, x);
    } else {
      RigidXml(c, path, x);
    }
  }
  x << "</worldbody>\n";
  return x.str();
}

// ------------------------------------------------------------------------------ ObstacleSet
ObstacleSet::ObstacleSet(const mjModel* m, const std::vector<ObstacleConfig>& cfg) {
  auto mocap = [m](const std::string& body) {
    const int id = MjIdOrThrow(m, mjOBJ_BODY, body, "obstacles");
    const int mid = m->body_mocapid[id];
    if (mid < 0) throw InputError("obstacles: body '" + body + "' is not a mocap body");
    return mid;
  };
  for (const ObstacleConfig& c : cfg) {
    Item item{c, ObstaclePath(c), {}, 0, 0};
    const std::string base = c.category + ":" + c.name;
    item.parts.push_back({mocap(base), Eigen::Vector3d::Zero(), 0});
    if (c.category == "person") {
      const double s = PersonScale(c);
      item.parts.push_back({mocap(base + "/leg_l"), {0, kHipY * s, kHipZ * s}, 1});
      item.parts.push_back({mocap(base + "/leg_r"), {0, -kHipY * s, kHipZ * s}, -1});
    } else if (c.category == "ball") {
      item.radius_m = 0.5 * BallDiameter(c);
      item.z_m = item.radius_m + kLift_m;
    } else {
      item.z_m = 0.5 * BoxSize(c).z() + kLift_m;
    }
    items_.push_back(std::move(item));
  }
}

Eigen::Quaterniond ObstacleSet::RollingQuat(const Item& item, double t) {
  // Rolling without slipping: each leg turns the ball about the horizontal axis normal to the
  // leg by length / radius. Whole cycles compose to one rotation, applied `cycle` times.
  const ObstaclePath& path = item.path;
  const ObstaclePath::Where w = path.Locate(t);
  if (w.leg < 0) return Eigen::Quaterniond::Identity();
  auto leg_rot = [&](const ObstaclePath::Leg& leg, double fraction) {
    if (leg.length_m <= 0) return Eigen::Quaterniond::Identity();
    const Eigen::Vector2d d = (leg.to_w - leg.from_w) / leg.length_m;
    const Eigen::Vector3d axis(-d.y(), d.x(), 0);  // z x d
    return Eigen::Quaterniond(Eigen::AngleAxisd(fraction * leg.length_m / item.radius_m, axis));
  };
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  if (w.cycle > 0) {
    Eigen::Quaterniond qc = Eigen::Quaterniond::Identity();
    for (const auto& leg : path.legs()) qc = leg_rot(leg, 1.0) * qc;
    Eigen::AngleAxisd aa(qc);
    aa.angle() *= static_cast<double>(w.cycle);
    q = Eigen::Quaterniond(aa);
  }
  for (int i = 0; i < w.leg; ++i) q = leg_rot(path.legs()[i], 1.0) * q;
  return (leg_rot(path.legs()[w.leg], w.fraction) * q).normalized();
}

void ObstacleSet::PartPose(const Item& item, const Part& part, double t, Eigen::Vector3d* p_w,
                           Eigen::Quaterniond* q_w) const {
  const Eigen::Vector2d xy = item.path.Position(t);
  const std::string& k = item.cfg.category;
  if (k == "ball") {
    *p_w = {xy.x(), xy.y(), item.z_m};
    *q_w = RollingQuat(item, t);
    return;
  }
  if (k != "person") {
    *p_w = {xy.x(), xy.y(), item.z_m};
    *q_w = YawQuat(item.cfg.yaw_deg * kPi / 180.0);
    return;
  }
  const Eigen::Quaterniond q_yaw = YawQuat(item.path.Yaw(t));
  *p_w = Eigen::Vector3d(xy.x(), xy.y(), 0) + q_yaw * part.p_o;
  *q_w = q_yaw;
  if (part.swing_sign != 0 && item.path.Moving(t)) {
    const double phase = 2 * kPi * item.path.Distance(t) / (kStride * PersonScale(item.cfg));
    const double swing = part.swing_sign * kSwingRad * std::sin(phase);
    *q_w = q_yaw * Eigen::Quaterniond(Eigen::AngleAxisd(swing, Eigen::Vector3d::UnitY()));
  }
}

void ObstacleSet::Apply(const mjModel* m, mjData* d, double t) const {
  (void)m;
  for (const Item& item : items_) {
    for (const Part& part : item.parts) {
      Eigen::Vector3d p;
      Eigen::Quaterniond q;
      PartPose(item, part, t, &p, &q);
      mjtNum* pos = d->mocap_pos + 3 * part.mocap_id;
      mjtNum* quat = d->mocap_quat + 4 * part.mocap_id;
      pos[0] = p.x(), pos[1] = p.y(), pos[2] = p.z();
      quat[0] = q.w(), quat[1] = q.x(), quat[2] = q.y(), quat[3] = q.z();
    }
  }
}

std::vector<ObstacleSet::State> ObstacleSet::StateAt(double t) const {
  std::vector<State> out;
  out.reserve(items_.size());
  for (const Item& item : items_) {
    State s;
    s.name = item.cfg.name;
    s.category = item.cfg.category;
    PartPose(item, item.parts[0], t, &s.p_w, &s.q_w);
    s.moving = item.path.Moving(t);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace viqu::sim

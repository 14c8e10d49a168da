// Scripted obstacles: exact path timing, the MJCF they produce, and the mocap bodies they move.
#include "sim/obstacles.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/errors.h"
#include "sim/mujoco_handles.h"

namespace viqu::sim {
namespace {

constexpr double kEps = 1e-9;

ObstacleConfig Walker(std::vector<Vec2> path, const std::string& loop, double pause_s = 0) {
  ObstacleConfig c;
  c.name = "alice";
  c.category = "person";
  c.path = std::move(path);
  c.speed_mps = 0.5;
  c.start_s = 2.0;
  c.pause_s = pause_s;
  c.loop = loop;
  c.yaw_deg = 45;
  return c;
}

void ExpectAt(const ObstaclePath& p, double t, double x, double y) {
  const Eigen::Vector2d xy = p.Position(t);
  EXPECT_NEAR(xy.x(), x, kEps) << "t = " << t;
  EXPECT_NEAR(xy.y(), y, kEps) << "t = " << t;
}

TEST(ObstaclePath, StandsUntilStartThenWalksAndStops) {
  // Two legs: 1 m along +x (2 s), then 1 m along +y (2 s), pause 1 s between.
  const ObstaclePath p(Walker({{0, 0}, {1, 0}, {1, 1}}, "none", 1.0));
  ExpectAt(p, 0.0, 0, 0);
  ExpectAt(p, 1.99, 0, 0);
  EXPECT_FALSE(p.Moving(1.0));
  EXPECT_NEAR(p.Yaw(1.0), M_PI / 4, kEps);  // yaw_deg while standing
  ExpectAt(p, 3.0, 0.5, 0);
  EXPECT_TRUE(p.Moving(3.0));
  EXPECT_NEAR(p.Yaw(3.0), 0, kEps);
  EXPECT_NEAR(p.Distance(3.0), 0.5, kEps);
  // Arrives at (1, 0) at t = 4, waits until t = 5 facing +x.
  ExpectAt(p, 4.5, 1, 0);
  EXPECT_FALSE(p.Moving(4.5));
  EXPECT_NEAR(p.Yaw(4.5), 0, kEps);
  ExpectAt(p, 6.0, 1, 0.5);
  EXPECT_TRUE(p.Moving(6.0));
  EXPECT_NEAR(p.Yaw(6.0), M_PI / 2, kEps);
  EXPECT_NEAR(p.Distance(6.0), 1.5, kEps);
  // Reaches (1, 1) at t = 7 and stays there.
  ExpectAt(p, 7.5, 1, 1);
  ExpectAt(p, 100.0, 1, 1);
  EXPECT_FALSE(p.Moving(7.5));
  EXPECT_FALSE(p.Moving(100.0));
  EXPECT_NEAR(p.Distance(100.0), 2.0, kEps);
  EXPECT_TRUE(p.Locate(100.0).finished);
}

TEST(ObstaclePath, PingpongTurnsAround) {
  const ObstaclePath p(Walker({{0, 0}, {2, 0}}, "pingpong"));
  // Out: t in [2, 6), back: [6, 10), then again.
  ExpectAt(p, 4.0, 1, 0);
  EXPECT_NEAR(p.Yaw(4.0), 0, kEps);
  ExpectAt(p, 7.0, 1.5, 0);
  EXPECT_NEAR(std::abs(p.Yaw(7.0)), M_PI, kEps);
  EXPECT_TRUE(p.Moving(7.0));
  ExpectAt(p, 9.0, 0.5, 0);
  ExpectAt(p, 11.0, 0.5, 0);  // second cycle, outward again
  EXPECT_NEAR(p.Yaw(11.0), 0, kEps);
  ExpectAt(p, 2.0 + 8.0 * 5 + 3.0, 1.5, 0);
  EXPECT_NEAR(p.Distance(11.0), 4.5, kEps);
  EXPECT_EQ(p.Locate(11.0).cycle, 1);
}

TEST(ObstaclePath, PingpongPausesAtBothEnds) {
  const ObstaclePath p(Walker({{0, 0}, {1, 0}}, "pingpong", 0.5));
  // Out [2, 4), pause [4, 4.5), back [4.5, 6.5), pause [6.5, 7), out again from 7.
  EXPECT_FALSE(p.Moving(4.25));
  ExpectAt(p, 4.25, 1, 0);
  EXPECT_TRUE(p.Moving(5.5));
  ExpectAt(p, 5.5, 0.5, 0);
  EXPECT_FALSE(p.Moving(6.75));
  ExpectAt(p, 6.75, 0, 0);
  EXPECT_TRUE(p.Moving(8.0));
  ExpectAt(p, 8.0, 0.5, 0);
  EXPECT_NEAR(p.cycle_s(), 5.0, kEps);
}

TEST(ObstaclePath, LoopReturnsToTheFirstPoint) {
  const ObstaclePath p(Walker({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, "loop"));
  // Square of 4 m at 0.5 m/s: 8 s per cycle from t = 2.
  ExpectAt(p, 2.0 + 7.0, 0, 0.5);  // on the closing leg (0, 1) -> (0, 0)
  EXPECT_NEAR(p.Yaw(9.0), -M_PI / 2, kEps);
  ExpectAt(p, 10.0, 0, 0);
  ExpectAt(p, 11.0, 0.5, 0);
  ExpectAt(p, 2.0 + 8.0 * 3 + 5.0, 0.5, 1);
  EXPECT_NEAR(p.cycle_length_m(), 4.0, kEps);
  EXPECT_NEAR(p.Distance(2.0 + 8.0 * 3 + 5.0), 14.5, kEps);
}

TEST(ObstaclePath, SinglePointNeverMoves) {
  ObstacleConfig c = Walker({{3, 4}}, "loop");
  const ObstaclePath p(c);
  for (double t : {0.0, 2.0, 5.0, 1000.0}) {
    ExpectAt(p, t, 3, 4);
    EXPECT_FALSE(p.Moving(t));
    EXPECT_NEAR(p.Yaw(t), M_PI / 4, kEps);
  }
}

TEST(ObstaclePath, RejectsBadConfig) {
  ObstacleConfig c = Walker({{0, 0}, {1, 0}}, "circle");
  EXPECT_THROW(ObstaclePath{c}, InputError);
  c = Walker({}, "none");
  EXPECT_THROW(ObstaclePath{c}, InputError);
  c = Walker({{0, 0}, {1, 0}}, "none");
  c.speed_mps = 0;
  EXPECT_THROW(ObstaclePath{c}, InputError);
  c = Walker({{0, 0}, {1, 0}}, "none");
  c.category = "dog";
  EXPECT_THROW(ObstaclePath{c}, InputError);
  c = Walker({{0, 0}, {1, 0}}, "none");
  c.category = "box";
  c.size_m = {0.3, 0.3};
  EXPECT_THROW(ObstaclePath{c}, InputError);
}

// ---------------------------------------------------------------------------------- MuJoCo
std::vector<ObstacleConfig> AllKinds() {
  std::vector<ObstacleConfig> v;
  v.push_back(Walker({{0, -2}, {0, 2}}, "pingpong"));
  ObstacleConfig box;
  box.name = "crate";
  box.category = "box";
  box.size_m = {0.5, 0.4, 0.45};
  box.path = {{1.5, 0}, {1.9, 0}};
  box.speed_mps = 0.1;
  box.start_s = 1.0;
  v.push_back(box);
  ObstacleConfig ball;
  ball.name = "red";
  ball.category = "ball";
  ball.size_m = {0.25};
  ball.path = {{-1, -1}, {-1, 1}, {-2, 1}};
  ball.speed_mps = 0.4;
  ball.loop = "loop";
  v.push_back(ball);
  ObstacleConfig cart;
  cart.name = "cart";
  cart.category = "furniture";
  cart.path = {{2, 2}};
  v.push_back(cart);
  return v;
}

ModelPtr LoadWithObstacles(const std::vector<ObstacleConfig>& cfg) {
  const std::string xml =
      "<mujoco><worldbody><geom name=\"floor\" type=\"plane\" size=\"5 5 .1\"/></worldbody>\n" +
      ObstaclesXml(cfg) + "</mujoco>\n";
  return LoadModelString(xml, "test_obstacles");
}

TEST(ObstaclesXml, LoadsWithoutWarnings) {
  TakeMujocoWarnings();
  ModelPtr m = LoadWithObstacles(AllKinds());
  EXPECT_TRUE(TakeMujocoWarnings().empty());
  for (const char* body : {"person:alice", "person:alice/leg_l", "person:alice/leg_r", "box:crate",
                           "ball:red", "furniture:cart"}) {
    const int id = mj_name2id(m.get(), mjOBJ_BODY, body);
    ASSERT_GE(id, 0) << body;
    EXPECT_GE(m->body_mocapid[id], 0) << body;
    EXPECT_EQ(m->body_parentid[id], 0) << body;
  }
  EXPECT_EQ(m->nmocap, 6);
  EXPECT_EQ(ObstaclesXml({}), "");
}

TEST(ObstaclesXml, RejectsDuplicateNames) {
  std::vector<ObstacleConfig> v = AllKinds();
  v.push_back(v.front());
  EXPECT_THROW(ObstaclesXml(v), InputError);
}

TEST(ObstacleSet, ThrowsWhenABodyIsMissing) {
  std::vector<ObstacleConfig> v = AllKinds();
  ModelPtr m = LoadWithObstacles({v[1]});
  EXPECT_THROW(ObstacleSet(m.get(), v), InputError);
}

TEST(ObstacleSet, ApplyPutsBodiesAtTheGroundTruth) {
  const std::vector<ObstacleConfig> cfg = AllKinds();
  ModelPtr m = LoadWithObstacles(cfg);
  DataPtr d(mj_makeData(m.get()));
  const ObstacleSet set(m.get(), cfg);
  for (double t : {0.0, 0.5, 3.3, 7.1, 12.9}) {
    set.Apply(m.get(), d.get(), t);
    mj_forward(m.get(), d.get());
    const auto states = set.StateAt(t);
    ASSERT_EQ(states.size(), cfg.size());
    for (const auto& s : states) {
      const int id = mj_name2id(m.get(), mjOBJ_BODY, (s.category + ":" + s.name).c_str());
      ASSERT_GE(id, 0);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(d->xpos[3 * id + k], s.p_w[k], 1e-9) << s.name;
      const Eigen::Quaterniond q(d->xquat[4 * id], d->xquat[4 * id + 1], d->xquat[4 * id + 2],
                                 d->xquat[4 * id + 3]);
      EXPECT_NEAR(std::abs(q.dot(s.q_w)), 1.0, 1e-9) << s.name;
      EXPECT_EQ(s.moving, ObstaclePath(cfg[&s - states.data()]).Moving(t));
    }
  }
  // The person walks along y; the box starts moving at 1 s and stops after 0.4 m at 5 s.
  EXPECT_TRUE(set.StateAt(3.0)[0].moving);
  EXPECT_FALSE(set.StateAt(0.5)[1].moving);
  EXPECT_TRUE(set.StateAt(3.0)[1].moving);
  EXPECT_FALSE(set.StateAt(5.5)[1].moving);
  EXPECT_NEAR(set.StateAt(5.5)[1].p_w.x(), 1.9, 1e-9);
  EXPECT_FALSE(set.StateAt(3.0)[3].moving);
}

Eigen::Quaterniond BodyQuat(const mjModel* m, const mjData* d, const char* name) {
  const int id = mj_name2id(m, mjOBJ_BODY, name);
  return {d->xquat[4 * id], d->xquat[4 * id + 1], d->xquat[4 * id + 2], d->xquat[4 * id + 3]};
}

TEST(ObstacleSet, LegsSwingWhileWalkingOnly) {
  const std::vector<ObstacleConfig> cfg = {Walker({{0, -2}, {0, 2}}, "none")};
  ModelPtr m = LoadWithObstacles(cfg);
  DataPtr d(mj_makeData(m.get()));
  const ObstacleSet set(m.get(), cfg);
  auto legs_at = [&](double t) {
    set.Apply(m.get(), d.get(), t);
    mj_forward(m.get(), d.get());
    return std::make_pair(BodyQuat(m.get(), d.get(), "person:alice/leg_l"),
                          BodyQuat(m.get(), d.get(), "person:alice/leg_r"));
  };
  // Standing before the start: legs keep the same pose.
  const auto a = legs_at(0.3), b = legs_at(1.7);
  EXPECT_NEAR(a.first.angularDistance(b.first), 0, 1e-12);
  // Walking: the left leg's orientation changes over a quarter stride, and the legs differ.
  const auto c = legs_at(3.0), e = legs_at(3.7);
  EXPECT_GT(c.first.angularDistance(e.first), 0.1);
  EXPECT_GT(c.first.angularDistance(c.second), 0.1);
  // Finished (t > 2 + 8): standing again.
  const auto f = legs_at(11.0), g = legs_at(15.0);
  EXPECT_NEAR(f.first.angularDistance(g.first), 0, 1e-12);
}

TEST(ObstacleSet, BallRollsWithoutSlipping) {
  const std::vector<ObstacleConfig> cfg = AllKinds();
  ModelPtr m = LoadWithObstacles(cfg);
  const ObstacleSet set(m.get(), cfg);
  // Along its first leg (+y) a 0.25 m ball turns by distance / radius about z x y = -x.
  const double t = 1.0;  // 0.4 m walked
  const Eigen::Quaterniond q = set.StateAt(t)[2].q_w;
  const Eigen::AngleAxisd expected(0.4 / 0.125, Eigen::Vector3d(-1, 0, 0));
  EXPECT_NEAR(q.angularDistance(Eigen::Quaterniond(expected)), 0, 1e-9);
}

}  // namespace
}  // namespace viqu::sim

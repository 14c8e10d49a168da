// The slip, contact and foot-force scoring of issue 55 item 6 on synthetic traces worked by hand:
// the true stances from per-step contact and sole velocity (debounce, travel, the crossing
// instant), detections per stance, one-to-one matching with the window's edges, latency, the
// travel bands, false detections per metre, and the contact score's transitions.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "runner/contact_score.h"
#include "runner/foot_truth.h"
#include "runner/slip_score.h"

namespace viqu {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr double kDt = 0.001;  // physics step (s)

using Contacts = std::array<bool, kNumLegs>;
using Velocities = std::array<Eigen::Vector3d, kNumLegs>;

Velocities Still() {
  Velocities v;
  v.fill(Eigen::Vector3d::Zero());
  return v;
}

// FL (leg 0) in the air at the start; steps 1..N, step k ending at k ms.
TEST(FootTruth, StanceTravelCrossingAndDebounce) {
  runner::FootTruth truth(0.003, 0.003);
  Contacts c{false, true, true, true};
  truth.Step(0, 0.0, c, Still());
  EXPECT_FALSE(truth.contact()[0]);
  EXPECT_TRUE(truth.contact()[1]);
  for (int k = 1; k <= 200; ++k) {
    Velocities v = Still();
    // FL: a one-step touch at 5 ms (a chatter: no stance); down from 10 ms; slides at 0.1 m/s
    // along x from 50 ms to 99 ms (50 steps: 5 mm); a one-step bounce into the air at 120 ms
    // (kept down, its travel counted); lifts off at 150 ms.
    c[0] = k == 5 || (k >= 10 && k < 150 && k != 120);
    if (k >= 50 && k < 100) v[0] = Eigen::Vector3d(0.1, 0, 0);
    if (k == 120) v[0] = Eigen::Vector3d(0, 0.5, 0);  // 0.5 mm sideways in the bounce step
    // FR rolls (sole at rest, centre moving: not here) and holds throughout.
    truth.Step(k * kMs, kDt, c, v);
    if (k == 11) {
      EXPECT_FALSE(truth.contact()[0]) << "not yet held 3 steps";
    }
    if (k == 12) {
      EXPECT_TRUE(truth.contact()[0]);
    }
  }
  const std::vector<runner::TrueStance> st = truth.Finish(200 * kMs);
  std::vector<runner::TrueStance> fl;
  for (const runner::TrueStance& s : st) {
    if (s.leg == 0) fl.push_back(s);
  }
  ASSERT_EQ(fl.size(), 1u) << "the 5 ms touch and the 120 ms bounce make no stance of their own";
  EXPECT_EQ(fl[0].touchdown_ns, 10 * kMs);
  EXPECT_EQ(fl[0].liftoff_ns, 150 * kMs);
  EXPECT_FALSE(fl[0].from_start);
  EXPECT_FALSE(fl[0].to_end);
  // 5 mm along x, then 0.5 mm along y: |(5, 0.5)| mm.
  EXPECT_NEAR(fl[0].travel_m, std::hypot(0.005, 0.0005), 1e-12);
  // The travel passes 3 mm on the 31st sliding step (3.1 mm at step 80; 3.0 at step 79 is not above).
  EXPECT_EQ(fl[0].crossed_ns, 80 * kMs);
  EXPECT_DOUBLE_EQ(fl[0].peak_speed_mps, 0.5);
  // The other feet: one stance each, from the start to the end, no travel.
  for (const runner::TrueStance& s : st) {
    if (s.leg == 0) continue;
    EXPECT_TRUE(s.from_start);
    EXPECT_TRUE(s.to_end);
    EXPECT_EQ(s.crossed_ns, -1);
    EXPECT_EQ(s.travel_m, 0.0);
  }
  // Only FL's stance is a true slip event.
  const std::vector<runner::SlipEvent> events = runner::TrueSlipEvents(st);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].leg, 0);
  EXPECT_EQ(events[0].crossed_ns, 80 * kMs);
}

// A slide that comes back (net travel) is a slip when the largest net displacement passed the
// threshold, and not when it stayed below it however long the path.
TEST(FootTruth, NetDisplacementNotPathLength) {
  runner::FootTruth truth(0.003, 0.0);
  Contacts c{true, true, true, true};
  truth.Step(0, 0.0, c, Still());
  for (int k = 1; k <= 100; ++k) {
    Velocities v = Still();
    // FL jitters 2 mm forward and back five times (20 mm of path, 2 mm net at most).
    v[0] = Eigen::Vector3d(((k - 1) / 10) % 2 == 0 ? 0.2 : -0.2, 0, 0);
    truth.Step(k * kMs, kDt, c, v);
  }
  const std::vector<runner::TrueStance> st = truth.Finish(100 * kMs);
  ASSERT_EQ(st.size(), 4u);
  EXPECT_NEAR(st[0].travel_m, 0.002, 1e-12);
  EXPECT_TRUE(runner::TrueSlipEvents(st).empty());
}

TEST(SlipScore, DetectionsAreOnePerStance) {
  runner::SlipDetectionBuilder b;
  const int64_t dt = 5 * kMs;
  for (int k = 0; k < 60; ++k) {
    Contacts contact{}, flag{};
    // FL in stance at samples 0-19 and 30-49; flagged at 5, 7-8 (one detection) and 40.
    contact[0] = k < 20 || (k >= 30 && k < 50);
    flag[0] = contact[0] && (k == 5 || k == 7 || k == 8 || k == 40);
    b.Add(k * dt, dt, contact, flag, {static_cast<double>(k), 0, 0, 0});
  }
  const std::vector<runner::SlipEvent> d = b.Finish();
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].start_ns, 5 * dt);
  EXPECT_EQ(d[0].end_ns, 9 * dt);
  EXPECT_EQ(d[0].size, 8.0);
  EXPECT_EQ(d[1].start_ns, 40 * dt);
}

runner::SlipEvent Truth(int leg, int64_t start_ms, int64_t end_ms, int64_t crossed_ms, double travel_m) {
  return runner::SlipEvent{leg, start_ms * kMs, end_ms * kMs, crossed_ms * kMs, travel_m, false};
}
runner::SlipEvent Detection(int leg, int64_t onset_ms) {
  return runner::SlipEvent{leg, onset_ms * kMs, onset_ms * kMs + 5 * kMs, -1, 20, false};
}

TEST(SlipScore, OneToOneWithinTheWindow) {
  // Four true events: FL 1000-1200 ms (4 mm, crossed at 1100), FL 2000-2200 (15 mm, crossed
  // 2050), FR 1000-1200 (40 mm, crossed 1010), BL 3000-3200 (5 mm, crossed 3100).
  std::vector<runner::SlipEvent> truth = {Truth(0, 1000, 1200, 1100, 0.004), Truth(0, 2000, 2200, 2050, 0.015),
                                          Truth(1, 1000, 1200, 1010, 0.040), Truth(2, 3000, 3200, 3100, 0.005)};
  std::vector<runner::SlipEvent> det = {
      Detection(0, 980),   // FL: onset 20 ms before the start: the window's edge, matches (latency -120 ms)
      Detection(0, 1150),  // FL again in the same event: the event is taken, a false detection
      Detection(0, 2241),  // FL 41 ms after the second event's end: outside, false
      Detection(1, 1240),  // FR 40 ms after the end: the edge, matches (latency 230 ms)
      Detection(3, 1100),  // BR: no true event of that foot, false
      Detection(2, 2979),  // BL 21 ms before the start: outside, false
  };
  runner::SlipScoreOptions opt;
  opt.match_before_s = 0.02;
  opt.match_after_s = 0.04;
  opt.path_length_m = 2.0;
  const runner::SlipScore s = runner::ScoreSlip(&truth, &det, opt);
  EXPECT_EQ(s.truth_events, 4);
  EXPECT_EQ(s.detected_events, 6);
  EXPECT_EQ(s.true_found, 2);
  EXPECT_EQ(s.detections_correct, 2);
  EXPECT_DOUBLE_EQ(s.precision, 2.0 / 6);
  EXPECT_DOUBLE_EQ(s.recall, 0.5);
  EXPECT_DOUBLE_EQ(s.false_per_m, 2.0);  // 4 false over 2 m
  // Latencies -120 and 230 ms: the median of two is their mean.
  EXPECT_DOUBLE_EQ(s.latency_ms_median, 55.0);
  // Bands: 3-10 mm FL 4 mm (found) and BL 5 mm (missed); 10-30 mm FL 15 mm (missed); over 30 FR (found).
  EXPECT_EQ(s.band_events[0], 2);
  EXPECT_EQ(s.band_found[0], 1);
  EXPECT_DOUBLE_EQ(s.recall_in_band(0), 0.5);
  EXPECT_DOUBLE_EQ(s.recall_in_band(1), 0.0);
  EXPECT_DOUBLE_EQ(s.recall_in_band(2), 1.0);
  // slip.csv names the matched ones; the truth rows carry the crossing.
  const std::string csv = runner::SlipCsv(truth, det);
  EXPECT_NE(csv.find("truth,FL,1.000,1.200,1.100,0.004,1\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("detected,FL,1.150,1.155,,20,0\n"), std::string::npos) << csv;
}

TEST(SlipScore, NothingToFindNothingDetected) {
  std::vector<runner::SlipEvent> truth, det;
  const runner::SlipScore s = runner::ScoreSlip(&truth, &det, runner::SlipScoreOptions{});
  EXPECT_EQ(s.precision, 1.0);
  EXPECT_EQ(s.recall, 1.0);
  EXPECT_TRUE(std::isnan(s.latency_ms_median));
  EXPECT_TRUE(std::isnan(s.false_per_m));  // no path
  EXPECT_TRUE(std::isnan(s.recall_in_band(0)));
}

TEST(ContactScore, AccuracyTransitionsAndForce) {
  // FL's true stances: from the start to 100 ms, and 200 ms to the end (300 ms).
  std::vector<runner::TrueStance> stances(2);
  stances[0] = runner::TrueStance{0, 0, 100 * kMs, 0, -1, 0, true, false};
  stances[1] = runner::TrueStance{0, 200 * kMs, 300 * kMs, 0, -1, 0, false, true};
  runner::ContactScorer scorer;
  const double nan = std::nan("");
  for (int k = 0; k < 60; ++k) {  // 5 ms samples, 0-295 ms
    const int64_t t = k * 5 * kMs;
    Contacts truth{}, est{};
    truth.fill(true);
    est.fill(true);
    truth[0] = t < 100 * kMs || t >= 200 * kMs;
    est[0] = t < 110 * kMs || t >= 195 * kMs;  // lifts off 10 ms late, touches down 5 ms early
    // FL's normal force: 2 N true, 2.3 N estimated in its first stance, no estimate in the second.
    std::array<double, kNumLegs> est_n{nan, nan, nan, nan}, true_n{0, 0, 0, 0};
    if (truth[0]) {
      true_n[0] = 2.0;
      est_n[0] = t < 100 * kMs ? 2.3 : nan;
    }
    scorer.Add(t, est, truth);
    scorer.AddForce(est_n, truth, true_n);
  }
  std::string csv;
  const runner::ContactScore s = scorer.Finish(stances, &csv);
  // FL disagrees at 100, 105 (estimate still down) and 195 (already down): 3 of 240 foot-samples.
  EXPECT_EQ(s.samples, 240);
  EXPECT_DOUBLE_EQ(s.accuracy, 237.0 / 240);
  EXPECT_EQ(s.touchdowns, 1);  // the first stance began with the run
  EXPECT_EQ(s.liftoffs, 1);    // the second ends with it
  EXPECT_EQ(s.touchdowns_paired, 1);
  EXPECT_DOUBLE_EQ(s.touchdown_err_ms_median, 5.0);
  EXPECT_DOUBLE_EQ(s.liftoff_err_ms_median, 10.0);
  EXPECT_EQ(s.force_samples, 20);  // 0-95 ms
  EXPECT_NEAR(s.normal_rmse_n, 0.3, 1e-12);
  EXPECT_NEAR(s.true_normal_mean_n, 2.0, 1e-12);
  EXPECT_NE(csv.find("FL,liftoff,0.100,0.110,10.0\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("FL,touchdown,0.200,0.195,-5.0\n"), std::string::npos) << csv;
}

}  // namespace
}  // namespace viqu

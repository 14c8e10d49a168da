// The adaptive dynamic test (slam/core/object_motion.h) and the dynamic-object stage
// (slam/core/dynamic_objects.h) on synthetic object tracks with stereo-like depth noise.
#include "slam/core/object_motion.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "slam/core/dynamic_objects.h"

namespace viqu::slam {
namespace {

constexpr int64_t kFrameNs = 50'000'000;  // 20 Hz
constexpr double kFx = 457.0;             // focal length of the default camera (px)
constexpr double kBf = kFx * 0.04;        // fx * baseline (px m)

// An object of `n` points about 1 m ahead of a camera at the world origin looking along +z,
// each with a fixed random descriptor; Observe() returns its snapshot after moving by
// `offset_w`, with the depth noise that stereo would give.
class SyntheticObject {
 public:
  SyntheticObject(int n, uint64_t seed) : rng_(seed) {
    std::uniform_real_distribution<double> lateral(-0.2, 0.2), depth(0.9, 1.1);
    std::uniform_int_distribution<int> byte(0, 255);
    descriptors_.create(n, 32, CV_8U);
    for (int i = 0; i < n; ++i) {
      // Drawn z, y, x (random_vector.h): the order GCC gave these three arguments of one call.
      const double z = depth(rng_), y = lateral(rng_), x = lateral(rng_);
      points_.emplace_back(x, y, z);
      for (int b = 0; b < 32; ++b) descriptors_.at<uint8_t>(i, b) = static_cast<uint8_t>(byte(rng_));
    }
  }
  // With `pixel_sigma_px` > 0 the points also carry the keypoint's position error across the ray,
  // and the snapshot says so (sigma_lateral_m); otherwise the error is along the ray only and the
  // snapshot states none across (the test is then isotropic).
  ObjectSnapshot Observe(int64_t t_ns, const Eigen::Vector3d& offset_w, double disparity_sigma_px = 0.5,
                         double pixel_sigma_px = 0.0) {
    ObjectSnapshot s;
    s.t_ns = t_ns;
    s.descriptors = descriptors_.clone();
    std::normal_distribution<double> unit(0.0, 1.0);
    for (const Eigen::Vector3d& p0 : points_) {
      const Eigen::Vector3d p = p0 + offset_w;
      const double sigma = p.z() * p.z() * disparity_sigma_px / kBf;
      Eigen::Vector3d q = p * (1.0 + sigma * unit(rng_) / p.z());  // error along the ray
      if (pixel_sigma_px > 0) {
        const double lateral = p.norm() * pixel_sigma_px / kFx;
        const Eigen::Vector3d a1 = p.cross(Eigen::Vector3d::UnitY()).normalized(), a2 = p.normalized().cross(a1);
        const double e1 = unit(rng_);
        const double e2 = unit(rng_);
        q += lateral * (e1 * a1 + e2 * a2);
        s.sigma_lateral_m.push_back(lateral);
      }
      s.p_w.push_back(q);
      s.sigma_m.push_back(sigma);
    }
    return s;
  }

  // Gives `n` randomly chosen points new random descriptors: the object changes its look (a
  // walking person's legs turn, cloth folds), so that over many frames little of it matches.
  void ChangeLook(int n) {
    std::uniform_int_distribution<int> row(0, descriptors_.rows - 1), byte(0, 255);
    for (int k = 0; k < n; ++k) {
      const int i = row(rng_);
      for (int b = 0; b < 32; ++b) descriptors_.at<uint8_t>(i, b) = static_cast<uint8_t>(byte(rng_));
    }
  }

 private:
  std::mt19937_64 rng_;
  std::vector<Eigen::Vector3d> points_;
  cv::Mat descriptors_;
};

// Frames until the track first says dynamic (-1: never) for an object that stands still for
// `still_frames` and then moves at `velocity` (m/s).
int FramesToDetect(const Eigen::Vector3d& velocity, int still_frames, int frames, uint64_t seed) {
  SyntheticObject obj(40, seed);
  ObjectMotionTrack track;
  const AdaptiveDynamicSettings s;
  for (int k = 0; k < frames; ++k) {
    const double moving_s = std::max(0, k - still_frames) * kFrameNs * 1e-9;
    if (track.Add(obj.Observe(k * kFrameNs, velocity * moving_s, 0.5, 0.5), s)) return k - still_frames;
  }
  return -1;
}

TEST(ObjectMotion, StaticObjectIsNeverDynamic) {
  for (uint64_t seed = 1; seed <= 5; ++seed) EXPECT_EQ(FramesToDetect(Eigen::Vector3d::Zero(), 0, 400, seed), -1) << seed;
}

TEST(ObjectMotion, WalkingPersonWithinAFewFrames) {
  const int frames = FramesToDetect({0.8, 0, 0}, 20, 100, 3);  // 0.8 m/s across the view
  EXPECT_GE(frames, 1);  // one judgement of motion drops it (drop_frames), tentatively
  EXPECT_LE(frames, 3);
}

// The first judgement of motion drops the object's features at once; the second in a row
// (confirm_frames) confirms it, and only then is it held. A single mismatched look of an object
// that stands makes it dynamic for that frame alone, and with drop_frames = confirm_frames never.
TEST(ObjectMotion, ATentativeDecisionDropsAtTheFirstMotionAndWaitsForTheConfirmation) {
  const AdaptiveDynamicSettings s;  // drop_frames 1, confirm_frames 2, hold 1 s
  AdaptiveDynamicSettings at_confirmation = s;
  at_confirmation.drop_frames = s.confirm_frames;
  for (uint64_t seed = 51; seed < 54; ++seed) {
    // A walker at 0.8 m/s (4 cm a frame) from frame 20.
    SyntheticObject walker(40, seed);
    ObjectMotionTrack track, old_track;
    int dropped = -1, confirmed = -1, dropped_at_confirmation = -1;
    for (int k = 0; k < 40; ++k) {
      const Eigen::Vector3d offset(0.8 * std::max(0, k - 20) * kFrameNs * 1e-9, 0, 0);
      const ObjectSnapshot snapshot = walker.Observe(k * kFrameNs, offset, 0.5, 0.5);
      const bool dynamic = track.Add(snapshot, s);
      if (dynamic && dropped < 0) dropped = k - 20;
      if (track.confirmed() && confirmed < 0) confirmed = k - 20;
      EXPECT_TRUE(!track.confirmed() || dynamic) << seed << " frame " << k;
      if (old_track.Add(snapshot, at_confirmation) && dropped_at_confirmation < 0) dropped_at_confirmation = k - 20;
    }
    EXPECT_GE(dropped, 1) << seed;  // the frame after the onset: 4 cm
    EXPECT_EQ(confirmed, dropped + 1) << seed;
    EXPECT_EQ(dropped_at_confirmation, confirmed) << seed;

    // A standing object whose frame 30 is displaced by 6 cm (a mismatched look, 1.2 m/s from its
    // neighbours: not too fast to be motion): tentatively dynamic on that frame, and on frame 50
    // when that look is the second-old reference; never confirmed, never held; never dropped
    // when drop_frames equals confirm_frames.
    SyntheticObject stander(40, seed + 10);
    ObjectMotionTrack standing, standing_old;
    for (int k = 0; k < 60; ++k) {
      const Eigen::Vector3d offset(k == 30 ? 0.06 : 0.0, 0, 0);
      const ObjectSnapshot snapshot = stander.Observe(k * kFrameNs, offset, 0.5, 0.5);
      EXPECT_EQ(standing.Add(snapshot, s), k == 30 || k == 50) << seed << " frame " << k;
      EXPECT_FALSE(standing.confirmed()) << seed << " frame " << k;
      EXPECT_FALSE(standing_old.Add(snapshot, at_confirmation)) << seed << " frame " << k;
    }
  }
}

// The confirmation dates the motion: the map points keep the observations of keyframes before
// that date, so a date after the onset keeps looks of an object that had moved, and one before it
// loses looks of it standing. The date is where the line through the last still look's
// displacement and the confirming look's meets zero. The walker at 0.8 m/s (4 cm a frame) and the
// crate at 0.1 m/s (5 mm a frame), both from frame 20: measured -3.3 to -8.8 ms and -21.2 to
// +5.6 ms from the onset (the still look's end alone dated the crate 0 to 100 ms late: 1 cm).
TEST(ObjectMotion, TheConfirmationDatesTheOnsetWithinAFrame) {
  const AdaptiveDynamicSettings s;  // lag 1 s
  for (double speed : {0.8, 0.1}) {
    for (uint64_t seed = 61; seed < 64; ++seed) {
      SyntheticObject obj(40, seed);
      ObjectMotionTrack track;
      const int64_t start_ns = 20 * kFrameNs;
      int k = 0;
      for (; k < 100 && !track.confirmed(); ++k) {
        const Eigen::Vector3d offset(speed * std::max(0, k - 20) * kFrameNs * 1e-9, 0, 0);
        track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s);
        if (!track.confirmed()) {
          EXPECT_EQ(track.motion_onset_ns(), 0) << speed << " seed " << seed << " frame " << k;
        }
      }
      ASSERT_TRUE(track.confirmed()) << speed << " seed " << seed;
      const double off_ms = (track.motion_onset_ns() - start_ns) * 1e-6;
      std::printf("speed %.1f m/s, seed %lu: dated %+.1f ms from the onset\n", speed, static_cast<unsigned long>(seed),
                  off_ms);
      EXPECT_LE(off_ms, 10.0) << speed << " seed " << seed;                 // 1 mm of the crate's travel
      EXPECT_GE(off_ms, -kFrameNs * 1e-6) << speed << " seed " << seed;  // one frame
    }
  }
}

TEST(ObjectMotion, SlowBoxWithinHalfASecond) {
  const int frames = FramesToDetect({0.1, 0, 0}, 20, 100, 4);  // 0.1 m/s, the pushed crate
  EXPECT_GE(frames, 1);
  EXPECT_LE(frames, 10);  // 0.5 s at 20 Hz
}

// standing_people's walkers, setting off: a second-old look of their legs no longer matches (the
// legs stood elsewhere) and between two frames they move 2-4 cm, too little beyond the noise, so
// the track waited for the previous frame to show it (0.25-0.45 s). Between the two, a look a
// quarter of a second old matches and shows 10-20 cm. Here an object changes a quarter of its look
// every frame (0.74 of its features survive a frame: 9 of 40 over 5 frames, 2 over 10, too few to
// judge at min_matches 6) and sets off at 0.3 m/s (1.5 cm a frame): only a look 2-8 frames old
// both matches and shows the motion.
TEST(ObjectMotion, AWalkerWhoseLookChangesIsJudgedAgainstAQuarterSecondOldLook) {
  const AdaptiveDynamicSettings s;  // lag 1 s, threshold 2 cm, min_matches 6
  for (uint64_t seed = 41; seed < 46; ++seed) {
    SyntheticObject obj(40, seed);
    ObjectMotionTrack track;
    int detected = -1;
    for (int k = 0; k < 60 && detected < 0; ++k) {
      obj.ChangeLook(12);
      const double moving_s = std::max(0, k - 30) * kFrameNs * 1e-9;
      const bool dynamic = track.Add(obj.Observe(k * kFrameNs, Eigen::Vector3d(0.3 * moving_s, 0, 0), 0.5, 0.5), s);
      if (k < 30) {
        EXPECT_FALSE(dynamic) << seed << " frame " << k;  // changing its look while it stands is no motion
      } else if (dynamic) {
        detected = k - 30;
      }
    }
    EXPECT_GE(detected, 2) << seed;  // two judgements of motion in a row, 1.5 cm a frame
    EXPECT_LE(detected, 8) << seed;  // 0.4 s
    EXPECT_GT(track.last().lag_s, 0.075) << seed;  // judged against an older look than the previous frame's
    EXPECT_LT(track.last().lag_s, 0.45) << seed;
  }
}

TEST(ObjectMotion, ApproachingAndTangentialMotionBothCount) {
  // Towards the camera (mask depth shrinks, the norm of world positions hardly changes for an
  // object circling the origin): both are world displacements.
  EXPECT_GT(FramesToDetect({0, 0, -0.3}, 20, 100, 5), 0);
  EXPECT_GT(FramesToDetect({0.2, 0.0, 0.0}, 20, 100, 6), 0);
}

// Stereo judges a point's position across the viewing ray far better than along it: at 2 m with
// the default camera, depth noise is 0.11 m per point and the keypoint's position 2 mm. A 4 cm
// step across the view is motion; the same step in depth is within the noise; an isotropic noise
// model (the depth error on every axis) would miss both.
TEST(ObjectMotion, AcrossTheViewIsJudgedFinerThanInDepth) {
  const AdaptiveDynamicSettings s;  // pixel_sigma_px 0.5, disparity_sigma_px 0.5
  for (uint64_t seed = 31; seed < 36; ++seed) {
    SyntheticObject obj(40, seed);
    const Eigen::Vector3d at_2m(0, 0, 1.0);
    const ObjectSnapshot ref = obj.Observe(0, at_2m, 0.5, 0.5);
    const MotionMeasurement across = MeasureMotion(ref, obj.Observe(kFrameNs, at_2m + Eigen::Vector3d(0.04, 0, 0), 0.5, 0.5), s);
    ASSERT_TRUE(across.judged) << seed;
    EXPECT_TRUE(across.moving) << seed << " displacement " << across.displacement_m << " threshold " << across.threshold_m;
    EXPECT_NEAR(across.displacement_w.x(), 0.04, 0.01) << seed;
    EXPECT_LT(across.std_error(1), 0.1 * across.std_error(0)) << seed;  // across vs along the ray
    const MotionMeasurement in_depth = MeasureMotion(ref, obj.Observe(kFrameNs, at_2m + Eigen::Vector3d(0, 0, 0.04), 0.5, 0.5), s);
    EXPECT_FALSE(in_depth.moving) << seed << " displacement " << in_depth.displacement_m;
    EXPECT_FALSE(in_depth.still) << seed;  // nor does one frame rule motion out
    // Snapshots without a lateral error: every axis takes the depth error, 4 cm across is missed.
    ObjectSnapshot iso_ref = ref, iso_cur = obj.Observe(kFrameNs, at_2m + Eigen::Vector3d(0.04, 0, 0), 0.5, 0.5);
    iso_ref.sigma_lateral_m.clear();
    iso_cur.sigma_lateral_m.clear();
    EXPECT_FALSE(MeasureMotion(iso_ref, iso_cur, s).moving) << seed;
  }
}

// Moves at `speed` (m/s, across the view) for `walk_frames`, stands still for `pause_frames`, then
// moves on; returns the frame after the stop at which the track releases the object (-1: never
// within the pause), and in `redetected` the frames after the restart until it is dynamic again
// (-1: not within `after_frames`).
int ReleaseAfterStop(double speed, int walk_frames, int pause_frames, int after_frames, uint64_t seed,
                     const AdaptiveDynamicSettings& s, int* redetected = nullptr) {
  SyntheticObject obj(40, seed);
  ObjectMotionTrack track;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  int k = 0;
  for (; k < walk_frames; ++k) {
    offset.x() = speed * k * kFrameNs * 1e-9;
    track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s);
  }
  EXPECT_TRUE(track.Add(obj.Observe(k++ * kFrameNs, offset, 0.5, 0.5), s));
  int released = -1;
  for (int j = 1; j < pause_frames; ++j, ++k) {
    if (!track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s) && released < 0) released = j;
  }
  if (redetected) *redetected = -1;
  for (int j = 1; j <= after_frames; ++j, ++k) {
    offset.x() += speed * kFrameNs * 1e-9;
    if (track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s) && redetected && *redetected < 0) *redetected = j;
  }
  return released;
}

// The truth of the scenarios calls an object moving while it moved in the last second. The last
// look that reaches back into the motion ends lag_s (1 s) after the stop; counted from there the
// hold kept the object 2 s after it stopped. A later look that starts after the stop and sees it
// stand still dates the motion to its start: released one hold (20 frames) after the stop.
TEST(ObjectMotion, ReleasedOneHoldAfterItStops) {
  const AdaptiveDynamicSettings s;  // lag 1 s, hold 1 s, stop_max_m 1 cm
  for (uint64_t seed = 7; seed < 10; ++seed) {
    for (double speed : {0.5, 0.1}) {  // a person, the pushed crate
      const int released = ReleaseAfterStop(speed, 40, 100, 0, seed, s);
      // Seen: 20-21 frames for the person, 19-20 for the crate (a look below 1 cm hides up to
      // 0.1 s of its motion).
      EXPECT_GE(released, 18) << seed << " speed " << speed;
      EXPECT_LE(released, 23) << seed << " speed " << speed;
    }
  }
  // Any still look (not moving by threshold_m beyond its errors) hides up to 0.2 s of the crate's
  // motion: dated by those, it is released early (seen: 16 frames).
  AdaptiveDynamicSettings any = s;
  any.stop_max_m = 1;
  for (uint64_t seed = 7; seed < 10; ++seed) EXPECT_LE(ReleaseAfterStop(0.1, 40, 100, 0, seed, any), 17) << seed;
  // Dated by the last look that saw motion, as before stop_max_m existed: lag plus hold.
  AdaptiveDynamicSettings undated = s;
  undated.stop_max_m = 0;
  const int released = ReleaseAfterStop(0.5, 40, 100, 0, 7, undated);
  EXPECT_GE(released, 34);  // seen: 37
  EXPECT_LE(released, 42);
}

// A walker who pauses for less than the hold stays dynamic through the pause; one who walks on
// soon after being released is dynamic again at the first judgement of motion, not after
// confirm_frames of them.
TEST(ObjectMotion, APauseShorterThanTheHoldIsBridgedAndARestartSoonAfterIsJudgedAtOnce) {
  AdaptiveDynamicSettings s;
  s.drop_frames = s.confirm_frames;  // no tentative decision: a fresh start waits for the confirmation
  for (uint64_t seed = 11; seed < 14; ++seed) {
    EXPECT_EQ(ReleaseAfterStop(0.8, 40, 16, 10, seed, s), -1) << seed;  // 0.8 s pause
    int restart = -1, fresh = -1;
    ASSERT_GE(ReleaseAfterStop(0.8, 40, 30, 10, seed, s, &restart), 20) << seed;  // released, then walks on
    ReleaseAfterStop(0.8, 40, 30 + 60, 10, seed, s, &fresh);  // walks on 3 s after the release
    EXPECT_GE(restart, 1) << seed;
    EXPECT_LT(restart, fresh) << seed;
  }
}

// Frames until a walker who paused `pause_frames` (and was released) is dynamic again after it
// walks on at 0.8 m/s changing its whole look every frame, so that no look can be judged (-1: not
// within 10 frames).
int RedetectedWhenNothingMatches(int pause_frames, uint64_t seed, const AdaptiveDynamicSettings& s) {
  SyntheticObject obj(40, seed);
  ObjectMotionTrack track;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  int k = 0;
  for (; k < 40; ++k, offset.x() += 0.04) track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s);
  bool released = false;
  for (int j = 0; j < pause_frames; ++j, ++k) released = !track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s);
  EXPECT_TRUE(released);
  for (int j = 1; j <= 10; ++j, ++k) {
    obj.ChangeLook(400);
    offset.x() += 0.04;
    if (track.Add(obj.Observe(k * kFrameNs, offset, 0.5, 0.5), s)) {
      EXPECT_FALSE(track.last().judged);
      return j;
    }
  }
  return -1;
}

// walking_people_far's carol: released at the end of a 1 s pause, she walked on for 1.5 s with
// her leg features matching 0-4 times between frames, never judged. Within hold_s of a release,
// changed_look_frames looks in a row that cannot be judged make her dynamic again; later they
// do not (an object long still whose look changes is not taken for a walker), nor with the rule off.
TEST(ObjectMotion, AWalkerWhoWalksOnUnmatchableSoonAfterItsReleaseIsDynamicAgain) {
  const AdaptiveDynamicSettings s;  // changed_look_frames 2, hold 1 s
  for (uint64_t seed = 21; seed < 24; ++seed) {
    EXPECT_EQ(RedetectedWhenNothingMatches(30, seed, s), 2) << seed;  // released at 20-21: walks on 0.5 s later
    EXPECT_EQ(RedetectedWhenNothingMatches(70, seed, s), -1) << seed;  // walks on 2.5 s after the release
    AdaptiveDynamicSettings off = s;
    off.changed_look_frames = 0;
    EXPECT_EQ(RedetectedWhenNothingMatches(30, seed, off), -1) << seed;
  }
}

TEST(ObjectMotion, TooFewMatchesAreNotJudged) {
  SyntheticObject obj(5, 8);
  AdaptiveDynamicSettings s;
  s.min_matches = 6;
  const MotionMeasurement m = MeasureMotion(obj.Observe(0, {0, 0, 0}), obj.Observe(kFrameNs, {1, 0, 0}), s);
  EXPECT_FALSE(m.judged);
  EXPECT_FALSE(m.moving);
}

TEST(ObjectMotion, MedianDisplacementResistsMismatches) {
  SyntheticObject obj(40, 9);
  const AdaptiveDynamicSettings s;
  ObjectSnapshot a = obj.Observe(0, {0, 0, 0}, 0.0), b = obj.Observe(kFrameNs, {0.05, 0, 0}, 0.0);
  for (int i = 0; i < 15; ++i) b.p_w[static_cast<size_t>(i)] += Eigen::Vector3d(0, 3.0, 0);  // 15 of 40 wrong
  const MotionMeasurement m = MeasureMotion(a, b, s);
  EXPECT_EQ(m.matches, 40);
  EXPECT_NEAR(m.displacement_w.x(), 0.05, 1e-9);
  EXPECT_NEAR(m.displacement_w.y(), 0.0, 1e-9);
}

// A person's two legs look alike. Seen 1 s ago with both legs, now with the far leg only (the
// near one has left the image at its edge) whose look now is that of the near leg then: matched
// against everything, the still person moves by the legs' spacing; reference points that would
// be out of view had the person stood still are not candidates, and the false motion goes.
TEST(ObjectMotion, LookAlikePartThatLeftTheViewIsNotMatched) {
  SyntheticObject near_leg(20, 21), far_leg(20, 22);
  const AdaptiveDynamicSettings s;
  ObjectSnapshot ref = near_leg.Observe(0, {-0.5, 0, 0}, 0.0);  // x < 0: out of the current view
  const ObjectSnapshot far_then = far_leg.Observe(0, {-0.32, 0, 0}, 0.0);
  for (size_t i = 0; i < far_then.size(); ++i) {
    ref.p_w.push_back(far_then.p_w[i]);
    ref.sigma_m.push_back(far_then.sigma_m[i]);
  }
  cv::vconcat(ref.descriptors, far_then.descriptors, ref.descriptors);
  ObjectSnapshot cur = far_leg.Observe(20 * kFrameNs, {-0.32, 0, 0}, 0.0);
  near_leg.Observe(0, {0, 0, 0}).descriptors.copyTo(cur.descriptors);  // the far leg now looks as the near one did

  const MotionMeasurement fooled = MeasureMotion(ref, cur, s);
  ASSERT_TRUE(fooled.judged);
  EXPECT_TRUE(fooled.moving);
  EXPECT_NEAR(fooled.displacement_m, 0.18, 0.05);
  const MotionMeasurement m =
      MeasureMotion(ref, cur, s, [](const Eigen::Isometry3d& T_c_w, const Eigen::Vector3d& p_w) { return (T_c_w * p_w).x() > -0.45; });
  EXPECT_FALSE(m.moving);
}

// The same person coming into view: the camera has turned so that the far leg, out of the
// reference view, is now seen, with the near leg's look then (the near leg hidden now). Matched
// against everything, the still person moves by the legs' spacing; current points that could not
// have been seen from the reference camera had the person stood still are not matched.
TEST(ObjectMotion, LookAlikePartThatEnteredTheViewIsNotMatched) {
  SyntheticObject near_leg(20, 23), far_leg(20, 24);
  const AdaptiveDynamicSettings s;
  const ObjectSnapshot ref = near_leg.Observe(0, {-0.32, 0, 0}, 0.0);  // reference camera at the origin
  // The far leg's points span x in [-0.9, -0.5]: all out of the reference view (x > -0.45).
  ObjectSnapshot cur = far_leg.Observe(20 * kFrameNs, {-0.7, 0, 0}, 0.0);
  near_leg.Observe(0, {0, 0, 0}).descriptors.copyTo(cur.descriptors);
  cur.T_c_w.translation() = Eigen::Vector3d(0.6, 0, 0);  // in this camera they span [-0.3, 0.1]
  const InViewIfStatic in_view = [](const Eigen::Isometry3d& T_c_w, const Eigen::Vector3d& p_w) {
    return (T_c_w * p_w).x() > -0.45;
  };
  for (const Eigen::Vector3d& p_w : ref.p_w) ASSERT_TRUE(in_view(cur.T_c_w, p_w));   // the reference leg is in view now
  for (const Eigen::Vector3d& p_w : cur.p_w) ASSERT_FALSE(in_view(ref.T_c_w, p_w));  // the current one was not then

  const MotionMeasurement fooled = MeasureMotion(ref, cur, s);
  ASSERT_TRUE(fooled.judged);
  EXPECT_TRUE(fooled.moving);
  EXPECT_NEAR(fooled.displacement_m, 0.38, 0.05);
  const MotionMeasurement m = MeasureMotion(ref, cur, s, in_view);
  EXPECT_EQ(m.matches, 0);
  EXPECT_FALSE(m.moving);
}

// Two frames whose points lie half a metre off in depth (the mask held the background behind a
// person, as seen in standing_then_walking), then the object as before; the object changes its
// look fast enough that only the previous frame matches it. Compared with the previous frame
// these are steps of 9 and 4.5 m/s, faster than anything followed here (max_speed_mps 3):
// mismatches, not motion. Taken as motion, two in a row make the standing object dynamic.
TEST(ObjectMotion, ADisplacementFasterThanAnyObjectIsAMismatch) {
  AdaptiveDynamicSettings no_limit;
  no_limit.max_speed_mps = 1000;
  for (uint64_t seed = 91; seed < 94; ++seed) {
    for (const AdaptiveDynamicSettings& s : {AdaptiveDynamicSettings{}, no_limit}) {
      SyntheticObject obj(60, seed);
      ObjectMotionTrack track;
      bool ever = false;
      for (int k = 0; k < 80; ++k) {
        obj.ChangeLook(25);  // a second or half a second back, nothing matches
        const double dz = k == 40 ? -0.45 : k == 41 ? -0.22 : 0.0;
        ever |= track.Add(obj.Observe(k * kFrameNs, {0, 0, dz}, 0.5, 0.5), s);
      }
      EXPECT_EQ(ever, s.max_speed_mps > 100) << seed;
    }
  }
}

// A relocalisation or a new map segment moves the world frame under the snapshots: the same
// standing object then lies 0.5 m away in world coordinates. Judged across the jump it "moves";
// with the measurements restarted at the jump, it stands.
TEST(ObjectMotion, MeasurementsRestartWhenTheWorldFrameJumps) {
  const AdaptiveDynamicSettings s;
  for (bool restart : {false, true}) {
    SyntheticObject obj(40, 81);
    ObjectMotionTrack track;
    bool ever = false;
    for (int k = 0; k < 60; ++k) {
      if (k == 30 && restart) track.RestartMeasurements();
      ever |= track.Add(obj.Observe(k * kFrameNs, {k >= 30 ? 0.5 : 0.0, 0, 0}, 0.5, 0.5), s);
    }
    EXPECT_EQ(ever, !restart) << restart;
  }
}

// The stage on hand-made frames: one person (id 3) and one box (id 5), 30 features each, plus
// 30 background features and 10 on furniture (id 7).
struct StageFixture {
  StereoCamera cam;
  SyntheticObject person{30, 11}, box{30, 12};
  StageFixture() {
    cam.width = 640;
    cam.height = 480;
    cam.fx = cam.fy = 457;
    cam.cx = 319.5;
    cam.cy = 239.5;
    cam.bf = kBf;
  }
  static std::vector<SegmentInstance> Instances(bool with_person = true) {
    std::vector<SegmentInstance> v = {{0, Category::kBackground, "background"}, {5, Category::kBox, "crate"},
                                      {7, Category::kFurniture, "table"}};
    if (with_person) v.push_back({3, Category::kPerson, "erin"});
    return v;
  }
  // Features of the two objects (moved by the offsets) with exact depth from the points.
  FrameFeatures Features(int64_t t_ns, const Eigen::Vector3d& person_w, const Eigen::Vector3d& box_w) {
    FrameFeatures f;
    std::vector<cv::Mat> rows;
    auto add = [&](const ObjectSnapshot& s, uint16_t id) {
      for (size_t i = 0; i < s.size(); ++i) {
        const Eigen::Vector2d uv = cam.Project(s.p_w[i]);
        f.keypoints.emplace_back(cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y())), 0);
        f.depth.push_back(static_cast<float>(s.p_w[i].z()));
        f.u_right.push_back(static_cast<float>(uv.x() - cam.bf / s.p_w[i].z()));
        f.object.push_back(id);
        rows.push_back(s.descriptors.row(static_cast<int>(i)));
      }
    };
    add(person.Observe(t_ns, person_w), 3);
    add(box.Observe(t_ns, box_w), 5);
    for (int i = 0; i < 40; ++i) {
      f.keypoints.emplace_back(cv::Point2f(10.f + i, 10.f), 0);
      f.depth.push_back(3.f);
      f.u_right.push_back(5.f + i);
      f.object.push_back(i < 10 ? 7 : 0);
      rows.push_back(cv::Mat::zeros(1, 32, CV_8U));
    }
    cv::vconcat(rows, f.descriptors);
    return f;
  }
};

int Dropped(const std::vector<bool>& keep) { return static_cast<int>(std::count(keep.begin(), keep.end(), false)); }

TEST(DynamicObjects, AdaptiveDropsTheWalkerAndKeepsTheStandingBox) {
  StageFixture fx;
  SlamSettings settings;
  DynamicObjects stage(settings, fx.cam);
  ASSERT_EQ(stage.method(), DynamicMethod::kAdaptive);
  int first_drop = -1;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d person(k < 10 ? 0.0 : 0.8 * (k - 10) * kFrameNs * 1e-9, 0, 0);
    const FrameFeatures f = fx.Features(k * kFrameNs, person, Eigen::Vector3d::Zero());
    const std::vector<bool> keep = stage.KeepMask(f, StageFixture::Instances());
    ASSERT_EQ(stage.reports().size(), 2u);  // person and box; furniture is not judged
    if (Dropped(keep) > 0 && first_drop < 0) first_drop = k;
    if (k >= 15) {
      EXPECT_EQ(Dropped(keep), 30) << k;  // exactly the person's features
      EXPECT_EQ(stage.reports()[0].dropped, 30);
      EXPECT_EQ(stage.reports()[1].dropped, 0);
    }
    stage.Update(k * kFrameNs, f, cv::Mat(), Eigen::Isometry3d::Identity(), {});
  }
  EXPECT_GE(first_drop, 12);
  EXPECT_LE(first_drop, 15);
}

// Stereo can match a feature on one of a person's legs with the look-alike other leg: a cluster
// of the person's features gets a depth far in front (standing_then_walking, other noise draws:
// 0.11 m for legs at 0.66 m). Here 12 of the standing person's 30 features read 0.2 of their
// depth for five frames: the cluster is more than the quartile, and judged on it alone the
// person would move 0.8 m. The stage keeps the person's densest depth band and its features.
TEST(DynamicObjects, AStereoMismatchClusterInFrontOfAStandingPersonIsNotMotion) {
  StageFixture fx;
  SlamSettings settings;
  DynamicObjects stage(settings, fx.cam);
  for (int k = 0; k < 40; ++k) {
    FrameFeatures f = fx.Features(k * kFrameNs, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    if (k >= 25 && k < 30) {
      for (size_t i = 0; i < 12; ++i) {  // the person's features come first
        ASSERT_EQ(f.object[i], 3);
        f.depth[i] *= 0.2f;
      }
    }
    const std::vector<bool> keep = stage.KeepMask(f, StageFixture::Instances());
    EXPECT_EQ(Dropped(keep), 0) << k;
    stage.Update(k * kFrameNs, f, cv::Mat(), Eigen::Isometry3d::Identity(), {});
    EXPECT_FALSE(stage.reports()[0].dynamic) << k;
  }
}

TEST(DynamicObjects, TurnedDynamicIsReportedOnceAndSurvivesAMissedDetection) {
  StageFixture fx;
  DynamicObjects stage(SlamSettings{}, fx.cam);
  int turned_count = 0;
  for (int k = 0; k < 30; ++k) {
    const Eigen::Vector3d person(0.8 * k * kFrameNs * 1e-9, 0, 0);
    const FrameFeatures f = fx.Features(k * kFrameNs, person, Eigen::Vector3d::Zero());
    const bool missed = k == 20;  // the detector misses the person for a frame
    stage.KeepMask(f, StageFixture::Instances(!missed));
    for (uint16_t id : stage.Update(k * kFrameNs, f, cv::Mat(), Eigen::Isometry3d::Identity(), {})) {
      EXPECT_EQ(id, 3);
      ++turned_count;
    }
    if (k == 21) {
      ASSERT_EQ(stage.reports().size(), 2u);
      EXPECT_TRUE(stage.reports()[0].dynamic);  // history kept through the miss
    }
  }
  EXPECT_EQ(turned_count, 1);
}

// The walker turns dynamic (its features are dropped, Update reports it) at the first judgement
// of motion and is confirmed (JustConfirmed: the caller culls its map points) one frame later,
// once each; with drop_frames = confirm_frames both come on the same frame.
TEST(DynamicObjects, ATentativeTurnCullsNothingUntilConfirmed) {
  for (int drop_frames : {1, 2}) {
    StageFixture fx;
    SlamSettings settings;
    settings.dynamic.adaptive.drop_frames = drop_frames;
    DynamicObjects stage(settings, fx.cam);
    int turned_at = -1, confirmed_at = -1, turned_count = 0, confirmed_count = 0;
    for (int k = 0; k < 40; ++k) {
      const Eigen::Vector3d person(k < 10 ? 0.0 : 0.8 * (k - 10) * kFrameNs * 1e-9, 0, 0);
      const FrameFeatures f = fx.Features(k * kFrameNs, person, Eigen::Vector3d::Zero());
      stage.KeepMask(f, StageFixture::Instances());
      for (uint16_t id : stage.Update(k * kFrameNs, f, cv::Mat(), Eigen::Isometry3d::Identity(), {})) {
        EXPECT_EQ(id, 3);
        turned_at = k;
        ++turned_count;
      }
      for (uint16_t id : stage.JustConfirmed()) {
        EXPECT_EQ(id, 3);
        confirmed_at = k;
        ++confirmed_count;
      }
    }
    EXPECT_EQ(turned_count, 1) << drop_frames;
    EXPECT_EQ(confirmed_count, 1) << drop_frames;
    EXPECT_GE(turned_at, 11) << drop_frames;
    EXPECT_EQ(confirmed_at, turned_at + 2 - drop_frames) << drop_frames;
  }
}

TEST(DynamicObjects, SemanticDropsEveryMovableNoneDropsNothing) {
  StageFixture fx;
  SlamSettings semantic;
  semantic.dynamic.method = "semantic";
  DynamicObjects s(semantic, fx.cam);
  const FrameFeatures f = fx.Features(0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(Dropped(s.KeepMask(f, StageFixture::Instances())), 60);  // person + box, not the furniture

  SlamSettings none;
  none.dynamic.method = "none";
  DynamicObjects n(none, fx.cam);
  for (int k = 0; k < 30; ++k) {
    const FrameFeatures g = fx.Features(k * kFrameNs, Eigen::Vector3d(0.05 * k, 0, 0), Eigen::Vector3d::Zero());
    EXPECT_EQ(Dropped(n.KeepMask(g, StageFixture::Instances())), 0);
    EXPECT_TRUE(n.Update(k * kFrameNs, g, cv::Mat(), Eigen::Isometry3d::Identity(), {}).empty());
  }
  SlamSettings visual;
  visual.mode = "visual";
  EXPECT_EQ(DynamicMethodOf(visual), DynamicMethod::kNone);
}

TEST(DynamicObjects, EgoMotionDoesNotMakeStaticObjectsDynamic) {
  // The camera moves 0.5 m/s sideways and turns; the objects stand still in the world. Features
  // are seen from the moving camera and judged with its (true) pose.
  StageFixture fx;
  DynamicObjects stage(SlamSettings{}, fx.cam);
  for (int k = 0; k < 60; ++k) {
    const double t = k * kFrameNs * 1e-9;
    Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();
    T_w_c.translation() = Eigen::Vector3d(0.5 * t, 0, -0.3 * t);
    T_w_c.linear() = Eigen::AngleAxisd(0.2 * t, Eigen::Vector3d::UnitY()).toRotationMatrix();
    // World points seen in the camera: transform the features' 3D points into the camera frame.
    FrameFeatures f = fx.Features(k * kFrameNs, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    for (size_t i = 0; i < 60; ++i) {
      const Eigen::Vector3d p_w = fx.cam.Unproject(f.keypoints[i].pt.x, f.keypoints[i].pt.y, f.depth[i]);
      const Eigen::Vector3d p_c = T_w_c.inverse() * p_w;
      const Eigen::Vector2d uv = fx.cam.Project(p_c);
      f.keypoints[i].pt = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
      f.depth[i] = static_cast<float>(p_c.z());
    }
    EXPECT_EQ(Dropped(stage.KeepMask(f, StageFixture::Instances())), 0) << k;
    stage.Update(k * kFrameNs, f, cv::Mat(), T_w_c.inverse(), {});
  }
}

// The stage with an instance image: the person's features stay put (a stance leg) while its mask
// moves 4 cm a frame across the view from frame 10 (18 px at its 1 m). The stage turns it
// dynamic, tentatively, on frame 11 and drops its features from frame 12; a mask that stays, or
// the mask's look switched off, keeps them.
TEST(DynamicObjects, AMaskThatMovesDropsAnObjectWhoseFeaturesStay) {
  const auto first_drop = [](double mask_speed_mps, double threshold_m) {
    StageFixture fx;
    SlamSettings settings;
    settings.dynamic.adaptive.silhouette_threshold_m = threshold_m;
    DynamicObjects stage(settings, fx.cam);
    const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int k = 0; k < 30; ++k) {
      const FrameFeatures f = fx.Features(k * kFrameNs, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
      const std::vector<bool> keep = stage.KeepMask(f, StageFixture::Instances());
      if (stage.reports()[0].dropped > 0) return k;
      const int shift_px = static_cast<int>(std::lround(mask_speed_mps * std::max(0, k - 10) * 0.05 * kFx / 1.0));
      cv::Mat ids(480, 640, CV_16U, cv::Scalar(0));
      ids(cv::Rect(200 + shift_px, 120, 240, 240) & cv::Rect(0, 0, 640, 480)).setTo(cv::Scalar(3));
      stage.Update(k * kFrameNs, f, ids, pose, {}, &pose);
    }
    return -1;
  };
  EXPECT_EQ(first_drop(0.8, 0.015), 12);
  EXPECT_EQ(first_drop(0.0, 0.015), -1);
  EXPECT_EQ(first_drop(0.8, 0.0), -1);
}

// A rectangular silhouette: columns [lo, hi] over rows 150-348, the right side meeting another
// object (id 9) when `one_sided`.
Silhouette RectSilhouette(int lo, int hi, bool one_sided) {
  Silhouette s;
  for (int v = 150; v < 350; v += kSilhouetteRowStep) {
    s.v.push_back(v);
    s.lo.push_back(lo);
    s.hi.push_back(one_sided ? -1 : hi);
  }
  s.frame_ids = {3, 9};
  if (one_sided) s.touches_hi = {9};
  return s;
}

StereoCamera TestCamera() {
  StereoCamera cam;
  cam.width = 640;
  cam.height = 480;
  cam.fx = cam.fy = kFx;
  cam.cx = 319.5;
  cam.cy = 239.5;
  cam.bf = kBf;
  return cam;
}

// A walker setting off whose matched features stay where they were (a stance leg, as on a camera
// 10 cm above the floor), while its body and mask move 4 cm a frame across the view, 1 m ahead:
// the mask makes it dynamic on the first frame of motion (the look 0.1 s back spans that one
// frame) and on every frame after, tentatively: the mask alone never confirms it (no hold, its map
// points stay). Without the mask's look it stays static.
TEST(ObjectMotion, AWalkerWhoseFeaturesStayIsDroppedByItsMask) {
  const StereoCamera cam = TestCamera();
  int dynamic_frames = 0;
  const auto first_dynamic = [&](const AdaptiveDynamicSettings& s, const StereoCamera* c, int* confirmed_at) {
    SyntheticObject obj(40, 91);
    ObjectMotionTrack track;
    int first = -1;
    *confirmed_at = -1;
    dynamic_frames = 0;
    for (int k = 0; k < 60; ++k) {
      ObjectSnapshot snap = obj.Observe(k * kFrameNs, Eigen::Vector3d::Zero(), 0.5, 0.5);
      const int shift_px = static_cast<int>(std::lround(0.04 * std::max(0, k - 30) * kFx / 1.0));
      snap.silhouette = RectSilhouette(250 + shift_px, 330 + shift_px, false);
      snap.depth_m = 1.0;
      const bool dynamic = track.Add(std::move(snap), s, {}, c);
      dynamic_frames += dynamic ? 1 : 0;
      if (dynamic && first < 0) first = k;
      if (track.confirmed() && *confirmed_at < 0) *confirmed_at = k;
    }
    return first;
  };
  AdaptiveDynamicSettings s;  // silhouette_threshold_m 0.015, silhouette_lag_s 0.1
  int confirmed = -1;
  EXPECT_EQ(first_dynamic(s, &cam, &confirmed), 31);
  EXPECT_EQ(dynamic_frames, 29);  // frames 31-59
  EXPECT_EQ(confirmed, -1);
  EXPECT_EQ(first_dynamic(s, nullptr, &confirmed), -1);  // no camera: no look at the mask
  s.silhouette_threshold_m = 0;
  EXPECT_EQ(first_dynamic(s, &cam, &confirmed), -1);
  EXPECT_EQ(confirmed, -1);
}

// A standing object 3 m away, one side of it meeting another object, whose mask grows and shrinks
// by a pixel from frame to frame (the detector model's boundary jitter): its free side moves by up
// to 2 px between frames, 1.3 cm at that distance. silhouette_growth_px (2) keeps that from being
// motion; without it the flicker makes the object dynamic.
TEST(ObjectMotion, AOneSidedMasksFlickerIsNoMotion) {
  const StereoCamera cam = TestCamera();
  const auto ever_dynamic = [&](const AdaptiveDynamicSettings& s) {
    SyntheticObject obj(40, 92);
    std::mt19937 rng(93);
    std::uniform_int_distribution<int> growth(-1, 1);
    ObjectMotionTrack track;
    int dynamic_frames = 0;
    for (int k = 0; k < 100; ++k) {
      ObjectSnapshot snap = obj.Observe(k * kFrameNs, Eigen::Vector3d(0, 0, 2.0), 0.5, 0.5);
      snap.silhouette = RectSilhouette(300 - growth(rng), 340, true);
      snap.depth_m = 3.0;
      dynamic_frames += track.Add(std::move(snap), s, {}, &cam) ? 1 : 0;
    }
    return dynamic_frames;
  };
  AdaptiveDynamicSettings s;
  s.silhouette_threshold_m = 0.01;
  EXPECT_EQ(ever_dynamic(s), 0);
  s.silhouette_growth_px = 0;
  EXPECT_GT(ever_dynamic(s), 0);
}

}  // namespace
}  // namespace viqu::slam

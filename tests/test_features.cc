// ORB features cover the image and stereo matching recovers depth, checked on a rendered stereo
// pair of the room against the renderer's metric depth.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "runner/robot_rig.h"
#include "sim/stereo_renderer.h"
#include "slam/features/orb_extractor.h"
#include "slam/features/pyramid_level.h"
#include "slam/features/stereo_matcher.h"

namespace viqu {
namespace {

struct RenderedPair {
  StereoFrame frame;
  cv::Mat left, right;  // grey
};

RenderedPair RenderRoom(double x, double y, double yaw_deg) {
  Scenario s;
  s.name = "features_test";
  s.world = std::string(VIQU_SOURCE_DIR) + "/models/worlds/room.xml";
  s.robot.model = std::string(VIQU_SOURCE_DIR) + "/models/rat/rat.xml";
  s.robot.start.xy = {x, y};
  s.robot.start.yaw_deg = yaw_deg;
  runner::RobotRig rig(s);
  sim::RenderOptions ro;
  ro.segmentation = false;
  sim::StereoRenderer renderer(rig.world().model(), ro);
  RenderedPair p;
  renderer.Render(rig.world().model(), rig.world().data(), &p.frame);
  cv::cvtColor(p.frame.left_rgb, p.left, cv::COLOR_RGB2GRAY);
  cv::cvtColor(p.frame.right_rgb, p.right, cv::COLOR_RGB2GRAY);
  return p;
}

// Share of the 16 x 12 coarse cells that hold at least one keypoint, among the cells that hold a
// FAST corner at the lowest threshold (cells with some texture).
double Coverage(const std::vector<cv::KeyPoint>& kps, const cv::Mat& grey) {
  std::vector<cv::KeyPoint> any;
  cv::FAST(grey, any, 7);
  const int nx = 16, ny = 12;
  std::vector<int> textured(nx * ny), covered(nx * ny);
  auto cell = [&](const cv::Point2f& p) {
    return std::min(ny - 1, int(p.y * ny / grey.rows)) * nx + std::min(nx - 1, int(p.x * nx / grey.cols));
  };
  for (const auto& k : any) textured[cell(k.pt)] = 1;
  for (const auto& k : kps) covered[cell(k.pt)] = 1;
  int t = 0, c = 0;
  for (int i = 0; i < nx * ny; ++i) {
    t += textured[i];
    c += textured[i] && covered[i];
  }
  return double(c) / t;
}

TEST(Features, OrbSpreadsOverTheImage) {
  const RenderedPair p = RenderRoom(0.0, 0.0, 30.0);
  slam::OrbExtractor orb;
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  orb.Extract(p.left, cv::Mat(), &kps, &desc);
  std::vector<cv::KeyPoint> plain;
  cv::Mat plain_desc;
  cv::ORB::create(1200)->detectAndCompute(p.left, cv::noArray(), plain, plain_desc);
  const double ours = Coverage(kps, p.left), opencv = Coverage(plain, p.left);
  std::printf("features %zu (descriptors %d), coverage of textured cells: ours %.1f%%, plain OpenCV ORB %.1f%%\n",
              kps.size(), desc.rows, 100 * ours, 100 * opencv);
  EXPECT_GE(kps.size(), 1000u);
  EXPECT_LE(kps.size(), 1200u);
  EXPECT_EQ(desc.rows, static_cast<int>(kps.size()));
  EXPECT_GT(ours, 0.9);
  EXPECT_GT(ours, opencv);
}

TEST(Features, MaskedPixelsGetNoFeatures) {
  const RenderedPair p = RenderRoom(0.0, 0.0, 30.0);
  cv::Mat mask(p.left.size(), CV_8U, cv::Scalar(255));
  mask(cv::Rect(200, 100, 240, 200)).setTo(0);
  slam::OrbExtractor orb;
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  orb.Extract(p.left, mask, &kps, &desc);
  int inside = 0;
  for (const auto& k : kps) inside += cv::Rect(200, 100, 240, 200).contains(cv::Point(cvRound(k.pt.x), cvRound(k.pt.y)));
  EXPECT_EQ(inside, 0);
  EXPECT_GE(kps.size(), 800u);
}

TEST(Features, StereoDepthMatchesRenderedDepth) {
  for (const bool centres : {false, true})
  for (const auto& view : {std::array<double, 3>{0.0, 0.0, 30.0}, std::array<double, 3>{-1.0, -1.0, 0.0}}) {
    const RenderedPair p = RenderRoom(view[0], view[1], view[2]);
    slam::OrbExtractorOptions orb_opt;
    orb_opt.level_pixel_centres = centres;
    slam::OrbExtractor orb(orb_opt);
    std::vector<cv::KeyPoint> kl, kr;
    cv::Mat dl, dr;
    orb.Extract(p.left, cv::Mat(), &kl, &dl);
    orb.Extract(p.right, cv::Mat(), &kr, &dr);
    // Each keypoint lies on a pixel of its level, by the mapping chosen.
    for (const cv::KeyPoint& k : kl) {
      const slam::PyramidLevel level(p.left.size(), orb.ScaleOfLevel(k.octave), centres);
      const double x = level.ToLevelX(k.pt.x), y = level.ToLevelY(k.pt.y);
      ASSERT_NEAR(x, std::round(x), 1e-3) << "octave " << k.octave;
      ASSERT_NEAR(y, std::round(y), 1e-3) << "octave " << k.octave;
    }
    slam::StereoMatcherOptions stereo_opt;
    stereo_opt.level_pixel_centres = centres;
    slam::StereoMatcher matcher(stereo_opt);
    const auto matches = matcher.Match(p.left, p.right, kl, dl, kr, dr, p.frame.intrinsics.fx, p.frame.baseline_m);
    // Features whose true depth is within the matcher's depth range should get a depth.
    const double max_depth = slam::StereoMatcherOptions().max_depth_baselines * p.frame.baseline_m;
    std::vector<double> rel;
    int in_range = 0;
    int on_edges = 0;
    for (size_t i = 0; i < kl.size(); ++i) {
      // A corner's depth is only defined where the surface around it is continuous: skip
      // features whose 5x5 depth neighbourhood spans more than 5% (occlusion boundaries).
      const int u = cvRound(kl[i].pt.x), v = cvRound(kl[i].pt.y);
      const cv::Rect win = cv::Rect(u - 2, v - 2, 5, 5) & cv::Rect(0, 0, p.left.cols, p.left.rows);
      double lo = 0, hi = 0;
      cv::minMaxLoc(p.frame.left_depth_m(win), &lo, &hi);
      const float truth = p.frame.left_depth_m.at<float>(v, u);
      if (truth <= 0 || lo <= 0) continue;
      if (hi > 1.05 * lo) {
        ++on_edges;
        continue;
      }
      in_range += truth < 0.95 * max_depth;
      if (matches[i].depth_m <= 0) continue;
      rel.push_back(std::abs(matches[i].depth_m - truth) / truth);
    }
    std::sort(rel.begin(), rel.end());
    ASSERT_FALSE(rel.empty());
    const double median = rel[rel.size() / 2], p90 = rel[rel.size() * 9 / 10];
    std::printf("%s view (%g, %g, %g deg): %zu left features (%d on depth edges, not scored), %d nearer than "
                "%.2f m, %zu of those with stereo depth, relative depth error median %.2f%% p90 %.2f%%\n",
                centres ? "level pixel centres" : "x * scale^l", view[0], view[1], view[2], kl.size(), on_edges,
                in_range, max_depth, rel.size(), 100 * median, 100 * p90);
    // At least half of the features within the depth range get a depth.
    EXPECT_GT(rel.size(), in_range / 2);
    EXPECT_LT(median, 0.02);
    EXPECT_LT(p90, 0.05);
  }
}

// The ground seen from the rat's low camera gains about half a pixel of disparity per image row, so
// an upright 11 x 11 window mixes rows whose disparities span 5 px. Windows sheared by the ground's
// slope follow it: on the rendered room's floor (features whose true disparity grows by more than
// 0.3 px per row, away from depth edges) the disparity error in pixels of the feature's pyramid
// level falls well below the upright window's.
TEST(Features, ShearedStereoWindowsFollowTheGround) {
  for (const auto& view : {std::array<double, 3>{0.0, 0.0, 30.0}, std::array<double, 3>{-1.0, -1.0, 0.0},
                           std::array<double, 3>{0.5, -0.5, 135.0}}) {
    const RenderedPair p = RenderRoom(view[0], view[1], view[2]);
    slam::OrbExtractor orb;
    std::vector<cv::KeyPoint> kl, kr;
    cv::Mat dl, dr;
    orb.Extract(p.left, cv::Mat(), &kl, &dl);
    orb.Extract(p.right, cv::Mat(), &kr, &dr);
    const double bf = p.frame.intrinsics.fx * p.frame.baseline_m;
    auto truth_disparity = [&](int u, int v) {
      const float z = p.frame.left_depth_m.at<float>(v, u);
      return z > 0 ? bf / z : 0.0;
    };
    double err[2][3] = {};  // [upright, sheared][count, sum of squares, count >= 0.5 level px]
    for (const bool sheared : {false, true}) {
      slam::StereoMatcherOptions opt;
      opt.max_shear = sheared ? 0.6 : 0.0;
      opt.shear_step = 0.2;
      const auto matches = slam::StereoMatcher(opt).Match(p.left, p.right, kl, dl, kr, dr, p.frame.intrinsics.fx,
                                                          p.frame.baseline_m);
      for (size_t i = 0; i < kl.size(); ++i) {
        if (matches[i].u_right < 0) continue;
        const int u = cvRound(kl[i].pt.x), v = cvRound(kl[i].pt.y);
        if (u < 3 || v < 3 || u + 3 >= p.left.cols || v + 3 >= p.left.rows) continue;
        double lo = 0, hi = 0;
        cv::minMaxLoc(p.frame.left_depth_m(cv::Rect(u - 3, v - 3, 7, 7)), &lo, &hi);
        if (lo <= 0 || hi > 1.1 * lo) continue;  // depth edge
        const double slope = (truth_disparity(u, v + 3) - truth_disparity(u, v - 3)) / 6;
        if (slope < 0.3) continue;  // not the ground
        const double level_err =
            (kl[i].pt.x - matches[i].u_right - truth_disparity(u, v)) / orb.ScaleOfLevel(kl[i].octave);
        double* e = err[sheared];
        e[0] += 1;
        e[1] += std::min(level_err * level_err, 1.0);  // a gross mismatch counts as 1 px
        e[2] += std::abs(level_err) >= 0.5;
      }
    }
    ASSERT_GT(err[0][0], 50);
    ASSERT_GT(err[1][0], 50);
    const double rms_upright = std::sqrt(err[0][1] / err[0][0]), rms_sheared = std::sqrt(err[1][1] / err[1][0]);
    std::printf("view (%g, %g, %g deg), ground features: upright %.0f matched, rms %.3f level px, %.1f%% >= 0.5 px; "
                "sheared %.0f matched, rms %.3f, %.1f%% >= 0.5 px\n",
                view[0], view[1], view[2], err[0][0], rms_upright, 100 * err[0][2] / err[0][0], err[1][0], rms_sheared,
                100 * err[1][2] / err[1][0]);
    // Measured (three views, equiangular sub-pixel in both): upright rms 0.51-0.56 level px with
    // 33-42% of matches off by half a pixel or more; sheared rms 0.20-0.21 with 1-3%, and more
    // ground features matched (the outlier test drops fewer). Bounds at about twice the sheared figures.
    EXPECT_LT(rms_sheared, 0.45);
    EXPECT_LT(rms_sheared, 0.6 * rms_upright);
    EXPECT_LT(err[1][2] / err[1][0], 0.08);
    EXPECT_GE(err[1][0], err[0][0]);
  }
}

// SAD costs are V-shaped about their minimum, so a parabola through three of them pulls the
// sub-pixel estimate towards whole pixels; lines of equal and opposite slope do not. A textured
// plane shifted by known fractional disparities: the equiangular fit's mean error is well below the
// parabola's.
TEST(Features, EquiangularSubpixelFollowsFractionalDisparity) {
  cv::Mat noise(120, 320, CV_32F);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.2);
  cv::Mat left;
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  noise.convertTo(left, CV_8U);
  std::vector<cv::KeyPoint> kps;
  for (int v = 20; v < 100; v += 8) {
    for (int u = 120; u < 300; u += 8) kps.emplace_back(cv::Point2f(u, v), 31.f, -1.f, 0.f, 0);
  }
  double abs_err[2] = {};
  int n[2] = {};
  for (int step = 0; step < 10; ++step) {
    const double d = 20 + 0.1 * step;
    // right(u, v) = left(u + d, v): a fronto-parallel plane at disparity d.
    cv::Mat map_x(left.size(), CV_32F), map_y(left.size(), CV_32F);
    for (int v = 0; v < left.rows; ++v) {
      for (int u = 0; u < left.cols; ++u) {
        map_x.at<float>(v, u) = static_cast<float>(u + d);
        map_y.at<float>(v, u) = static_cast<float>(v);
      }
    }
    cv::Mat right;
    cv::remap(left, right, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
    for (const int equiangular : {0, 1}) {
      slam::StereoMatcherOptions opt;
      opt.subpixel = equiangular ? "equiangular" : "parabola";
      opt.sad_uniqueness = 1.0;  // every feature: this test scores the sub-pixel fit, not rejection
      opt.sad_outlier_factor = 100;
      const auto m = slam::StereoMatcher(opt).Match(left, right, kps, cv::Mat(), {}, cv::Mat(), 400, 0.1);
      for (size_t i = 0; i < kps.size(); ++i) {
        if (m[i].u_right < 0) continue;
        abs_err[equiangular] += std::abs(kps[i].pt.x - m[i].u_right - d);
        ++n[equiangular];
      }
    }
  }
  ASSERT_GT(n[0], 1500);
  ASSERT_GT(n[1], 1500);
  const double parabola = abs_err[0] / n[0], equiangular = abs_err[1] / n[1];
  std::printf("mean |disparity error| over disparities 20.0 .. 20.9: parabola %.4f px (%d), equiangular %.4f px (%d)\n",
              parabola, n[0], equiangular, n[1]);
  // Measured: parabola 0.071 px, equiangular 0.024 px.
  EXPECT_LT(equiangular, 0.05);
  EXPECT_LT(equiangular, 0.6 * parabola);
}

// A foreground strip at disparity 22 in front of a background at disparity 10: the 12 left-image
// columns just left of the strip show background that the strip hides from the right camera, so
// no match there can be right (an occlusion). The left-right check drops those matches and no
// other: away from the strip's edges every match is the same with the check as without.
TEST(Features, LeftRightCheckDropsOccludedMatchesOnly) {
  cv::RNG rng(11);
  auto texture = [&rng](int rows, int cols) {
    cv::Mat noise(rows, cols, CV_32F), out;
    rng.fill(noise, cv::RNG::NORMAL, 0, 1);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.2);
    cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
    noise.convertTo(out, CV_8U);
    return out;
  };
  const int rows = 80, cols = 400, d = 10, D = 22, strip_lo = 200, strip_hi = 260;  // the strip's left-image columns
  const cv::Mat back = texture(rows, cols + D), front = texture(rows, cols + D);
  cv::Mat left(rows, cols, CV_8U), right(rows, cols, CV_8U);
  for (int v = 0; v < rows; ++v) {
    for (int u = 0; u < cols; ++u) {
      left.at<uchar>(v, u) = (u >= strip_lo && u < strip_hi) ? front.at<uchar>(v, u) : back.at<uchar>(v, u);
      // right(u) shows what the left camera sees at u + disparity: the strip where u + D falls on it.
      const bool on_strip = u + D >= strip_lo && u + D < strip_hi;
      right.at<uchar>(v, u) = on_strip ? front.at<uchar>(v, u + D) : back.at<uchar>(v, u + d);
    }
  }
  // Sensor noise on each image, so that no match is exact (the outlier test scales with the median SAD).
  for (cv::Mat* img : {&left, &right}) {
    cv::Mat n(rows, cols, CV_16S);
    rng.fill(n, cv::RNG::NORMAL, 0, 2);
    cv::Mat wide;
    img->convertTo(wide, CV_16S);
    wide += n;
    wide.convertTo(*img, CV_8U);
  }
  std::vector<cv::KeyPoint> kps;
  for (int v = 10; v < rows - 10; v += 3) {
    for (int u = 40; u < cols - 20; ++u) kps.emplace_back(cv::Point2f(u, v), 31.f, -1.f, 0.f, 0);
  }
  auto match = [&](double lr_check_px) {
    slam::StereoMatcherOptions opt;
    opt.sad_uniqueness = 1.0;  // every feature gets its row's SAD minimum: what the check drops is scored
    opt.sad_outlier_factor = 100;
    opt.lr_check_px = lr_check_px;
    return slam::StereoMatcher(opt).Match(left, right, kps, cv::Mat(), {}, cv::Mat(), 400, 0.1);
  };
  const auto off = match(0), on = match(0.5);
  const int h = slam::StereoMatcherOptions().sad_half_window;
  int occluded = 0, occluded_off = 0, occluded_on = 0, clear = 0, clear_same = 0, clear_right = 0;
  for (size_t i = 0; i < kps.size(); ++i) {
    const int u = static_cast<int>(kps[i].pt.x);
    if (u >= strip_lo - (D - d) && u < strip_lo) {  // background hidden from the right camera
      ++occluded;
      occluded_off += off[i].u_right >= 0;
      occluded_on += on[i].u_right >= 0;
    } else if (u + h < strip_lo - (D - d) || (u - h >= strip_lo && u + h < strip_hi) || u - h >= strip_hi) {
      ++clear;  // the whole window on one surface, seen by both cameras
      const double truth = (u >= strip_lo && u < strip_hi) ? D : d;
      clear_right += off[i].u_right >= 0 && std::abs(kps[i].pt.x - off[i].u_right - truth) < 0.5;
      clear_same += on[i].u_right == off[i].u_right;
    }
  }
  std::printf("occluded: %d features, matched %d without the check, %d with it; clear: %d, %d right, %d the same\n",
              occluded, occluded_off, occluded_on, clear, clear_right, clear_same);
  ASSERT_GT(occluded, 200);
  EXPECT_GT(occluded_off, 0.9 * occluded);   // every row has some minimum: wrong depths without the check
  EXPECT_LT(occluded_on, 0.2 * occluded);    // measured 16 of 240
  EXPECT_EQ(clear_right, clear);             // the scene is matched right where it can be
  EXPECT_EQ(clear_same, clear);              // and the check leaves those matches alone
}

// A pixel of pyramid level l lies at (x + 0.5) * cols / level_cols - 0.5 in the image, which is
// where cv::resize samples it: a smooth blob resized to each level and found there by its
// centroid maps back onto its image position. x * 1.2^l (the mapping before) misses by up to
// (1.2^l - 1) / 2 px plus the level's rounded size (0.4 px at level 7 for the second blob).
TEST(Features, PyramidLevelMapsLevelPixelsOntoTheImage) {
  const cv::Size image(640, 480);
  for (int l = 1; l < 8; ++l) {
    const double s = std::pow(1.2, l);
    const slam::PyramidLevel level(image, s);
    EXPECT_EQ(level.size(), cv::Size(cvRound(640 / s), cvRound(480 / s)));
    for (const cv::Point2d c : {cv::Point2d(200.3, 180.7), cv::Point2d(430.6, 300.2)}) {
      // Wide enough (6 level pixels) that point sampling by the bilinear resize keeps its centroid.
      const double sigma = 6.0 * s;
      cv::Mat img(image, CV_32F);
      for (int v = 0; v < img.rows; ++v) {
        for (int u = 0; u < img.cols; ++u) {
          const double r2 = (u - c.x) * (u - c.x) + (v - c.y) * (v - c.y);
          img.at<float>(v, u) = static_cast<float>(std::exp(-0.5 * r2 / (sigma * sigma)));
        }
      }
      cv::Mat small;
      cv::resize(img, small, level.size(), 0, 0, cv::INTER_LINEAR);
      double sw = 0, sx = 0, sy = 0;
      for (int v = 0; v < small.rows; ++v) {
        for (int u = 0; u < small.cols; ++u) {
          const double w = small.at<float>(v, u);
          sw += w;
          sx += w * u;
          sy += w * v;
        }
      }
      const double xl = sx / sw, yl = sy / sw;
      EXPECT_NEAR(level.ToImageX(xl), c.x, 0.02) << "level " << l;
      EXPECT_NEAR(level.ToImageY(yl), c.y, 0.02) << "level " << l;
      EXPECT_NEAR(level.ToLevelX(level.ToImageX(xl)), xl, 1e-9);
      EXPECT_NEAR(level.ToLevelY(level.ToImageY(yl)), yl, 1e-9);
    }
  }
}

}  // namespace

}  // namespace viqu

#include "slam/features/stereo_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/features/hamming.h"
#include "slam/features/pyramid_level.h"

namespace viqu::slam {
namespace {

// Columns searched either side of the upright SAD minimum with sheared windows (level px): at the
// ground's half a pixel per row the upright minimum lies within a pixel or two of the sheared one.
constexpr int kShearColumns = 3;

int Hamming(const cv::Mat& a, int ra, const cv::Mat& b, int rb) {
  return HammingDistance(a.ptr<uint8_t>(ra), b.ptr<uint8_t>(rb), a.cols);
}

// SADs between the (2h+1)^2 patch of `l` centred at (xl, y) and the patches of `r` centred at
// (x0 + k, y), k = 0 .. n-1, into acc[k], with the right patch's row y + dy shifted by
// -round(shear * dy) columns (shear: disparity gained per row downwards; 0 for an upright window).
// Integer sums, exact in any order, so the SSE2 and plain loops give the same numbers.
void SadRowSheared(const cv::Mat& l, const cv::Mat& r, int xl, int x0, int y, int h, double shear, int n,
                   std::vector<int>* acc) {
  acc->assign(n, 0);
  int* a = acc->data();
  const int reach = static_cast<int>(std::lround(std::abs(shear) * h));
#if defined(__SSE2__)
  // A patch row of up to 16 pixels is one SSE2 sum of absolute differences (psadbw) on 16 loaded
  // bytes, the ones past the row masked off: 6 shears x 9 columns per feature cost 4.3 ms a frame
  // in scalar code (bench_features, README). Only where all 16 bytes lie inside the image rows.
  const int w = 2 * h + 1;
  if (w <= 16 && xl - h + 16 <= l.cols && x0 + n - 1 + reach - h + 16 <= r.cols) {
    alignas(16) uchar m[16];
    for (int i = 0; i < 16; ++i) m[i] = i < w ? 0xFF : 0;
    const __m128i mask = _mm_load_si128(reinterpret_cast<const __m128i*>(m));
    for (int dy = -h; dy <= h; ++dy) {
      const int off = -static_cast<int>(std::lround(shear * dy));
      const __m128i vl = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(l.ptr<uchar>(y + dy) + xl - h)), mask);
      const uchar* pr = r.ptr<uchar>(y + dy) + x0 + off - h;
      for (int k = 0; k < n; ++k) {
        const __m128i vr = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(pr + k)), mask);
        const __m128i sad = _mm_sad_epu8(vl, vr);
        a[k] += _mm_cvtsi128_si32(sad) + _mm_extract_epi16(sad, 4);
      }
    }
    return;
  }
#endif
  for (int dy = -h; dy <= h; ++dy) {
    const int off = -static_cast<int>(std::lround(shear * dy));
    const uchar* pl = l.ptr<uchar>(y + dy) + xl;
    const uchar* pr = r.ptr<uchar>(y + dy) + x0 + off;
    for (int dx = -h; dx <= h; ++dx) {
      const int lv = pl[dx];
      const uchar* q = pr + dx;
      for (int k = 0; k < n; ++k) a[k] += std::abs(lv - int(q[k]));
    }
  }
}

// The upright window's SADs for columns x0 .. x0 + n - 1 into sad[k]. For a long run of columns (a
// search without a descriptor match, up to the whole disparity range) the loop runs over the
// columns innermost, contiguous in `r`, which the compiler vectorises (one left pixel against n
// right pixels) instead of an 11-pixel patch row per column.
void SadRow(const cv::Mat& l, const cv::Mat& r, int xl, int x0, int y, int h, int n, std::vector<int>* acc,
            std::vector<double>* sad) {
  sad->resize(n);
  if (n < 16) {
    // A few columns (around a descriptor match): a patch row per column (SSE2 where it can).
    SadRowSheared(l, r, xl, x0, y, h, 0.0, n, acc);
    for (int k = 0; k < n; ++k) (*sad)[k] = (*acc)[k];
    return;
  }
  acc->assign(n, 0);
  int* a = acc->data();
  for (int dy = -h; dy <= h; ++dy) {
    const uchar* pl = l.ptr<uchar>(y + dy) + xl;
    const uchar* pr = r.ptr<uchar>(y + dy) + x0;
    for (int dx = -h; dx <= h; ++dx) {
      const int lv = pl[dx];
      const uchar* q = pr + dx;
      for (int k = 0; k < n; ++k) a[k] += std::abs(lv - int(q[k]));
    }
  }
  for (int k = 0; k < n; ++k) (*sad)[k] = a[k];
}

}  // namespace

std::vector<StereoMatch> StereoMatcher::Match(const cv::Mat& left_grey, const cv::Mat& right_grey,
                                              const std::vector<cv::KeyPoint>& left_kps, const cv::Mat& left_desc,
                                              const std::vector<cv::KeyPoint>& right_kps, const cv::Mat& right_desc,
                                              double fx, double baseline_m) const {
  std::vector<StereoMatch> out(left_kps.size());
  const double min_disp = 0.0;
  const double max_disp = fx * baseline_m / opt_.min_depth_m;
  // Right keypoints by row, so each left feature looks only at its band.
  std::vector<std::vector<int>> rows(right_grey.rows);
  for (size_t j = 0; j < right_kps.size(); ++j) {
    const double band = opt_.row_band_px * std::pow(opt_.scale_factor, right_kps[j].octave);
    const int lo = std::max(0, static_cast<int>(std::floor(right_kps[j].pt.y - band)));
    const int hi = std::min(right_grey.rows - 1, static_cast<int>(std::ceil(right_kps[j].pt.y + band)));
    for (int r = lo; r <= hi; ++r) rows[r].push_back(static_cast<int>(j));
  }
  // Pyramids for the SAD refinement, built on demand per level.
  std::vector<cv::Mat> pyr_l, pyr_r;
  auto level = [&](std::vector<cv::Mat>& pyr, const cv::Mat& base, int l) -> const cv::Mat& {
    if (pyr.size() <= static_cast<size_t>(l)) pyr.resize(l + 1);
    if (pyr[l].empty()) {
      if (l == 0) pyr[l] = base;
      else cv::resize(base, pyr[l], PyramidLevel(base.size(), std::pow(opt_.scale_factor, l)).size(), 0, 0, cv::INTER_LINEAR);
    }
    return pyr[l];
  };

  // Sub-pixel offset of the minimum from the SAD costs at the best column and its two neighbours.
  const bool equiangular = opt_.subpixel == "equiangular";
  auto SubPixel = [equiangular](double c0, double c1, double c2) {
    if (equiangular) {
      const double rise = std::max(c0, c2) - c1;
      return rise > 0 ? (c0 - c2) / (2 * rise) : 0.0;
    }
    const double denom = 2 * (c0 + c2 - 2 * c1);
    return denom > 0 ? (c0 - c2) / denom : 0.0;
  };
  std::vector<double> best_sad(left_kps.size(), -1);  // SAD at the refined match, -1 if none
  std::vector<int> acc;
  std::vector<double> sad;
  for (size_t i = 0; i < left_kps.size(); ++i) {
    const cv::KeyPoint& kl = left_kps[i];
    const int row = cvRound(kl.pt.y);
    if (row < 0 || row >= left_grey.rows) continue;
    int best = std::numeric_limits<int>::max(), second = best, best_j = -1;
    for (int j : rows[row]) {
      const cv::KeyPoint& kr = right_kps[j];
      if (std::abs(kr.octave - kl.octave) > 1) continue;
      const double d = kl.pt.x - kr.pt.x;
      if (d < min_disp || d > max_disp) continue;
      const int dist = Hamming(left_desc, static_cast<int>(i), right_desc, j);
      if (dist < best) {
        second = best;
        best = dist;
        best_j = j;
      } else if (dist < second) {
        second = dist;
      }
    }
    const bool by_descriptor = best_j >= 0 && best < opt_.max_hamming &&
                               // Repeated texture (bricks, tiles) gives several similar candidates
                               // along a row: keep only a match clearly better than the runner-up.
                               !(second < std::numeric_limits<int>::max() && best > opt_.max_ratio * second);
    if (!by_descriptor) best_j = -1;

    // SAD along the row at the left feature's level: around the descriptor match, or, without
    // one (the right image has no keypoint at this corner), over the whole disparity range.
    // The level's pixel grid, mapped to the image as the extractor maps its keypoints.
    const PyramidLevel grid(left_grey.size(), std::pow(opt_.scale_factor, kl.octave), opt_.level_pixel_centres);
    const cv::Mat& L = level(pyr_l, left_grey, kl.octave);
    const cv::Mat& R = level(pyr_r, right_grey, kl.octave);
    const int h = opt_.sad_half_window;
    const int xl = cvRound(grid.ToLevelX(kl.pt.x)), yl = cvRound(grid.ToLevelY(kl.pt.y));
    if (yl - h < 0 || yl + h >= L.rows || xl - h < 0 || xl + h >= L.cols) continue;
    int lo = 0, hi = 0;  // candidate right columns at the level, inclusive
    if (by_descriptor) {
      const int xr0 = cvRound(grid.ToLevelX(right_kps[best_j].pt.x));
      lo = xr0 - opt_.sad_search_px;
      hi = xr0 + opt_.sad_search_px;
    } else {
      lo = xl - static_cast<int>(std::floor(max_disp / grid.scale_x()));
      hi = xl - 1;
    }
    lo = std::max(lo, h + 1);
    hi = std::min(hi, R.cols - h - 2);
    if (hi < lo) continue;
    SadRow(L, R, xl, lo - 1, yl, h, hi - lo + 3, &acc, &sad);  // columns lo-1 .. hi+1
    const int arg = static_cast<int>(std::min_element(sad.begin() + 1, sad.end() - 1) - sad.begin());
    if (!by_descriptor) {
      // Accept a search without a descriptor only if its minimum is unique along the row.
      double runner_up = std::numeric_limits<double>::max();
      for (int k = 1; k + 1 < static_cast<int>(sad.size()); ++k) {
        if (std::abs(k - arg) > 2) runner_up = std::min(runner_up, sad[k]);
      }
      if (sad[arg] > opt_.sad_uniqueness * runner_up) continue;
    }
    int col = lo - 1 + arg;  // best right column at the level
    double c0 = sad[arg - 1], c1 = sad[arg], c2 = sad[arg + 1];
    double shear = 0;  // of the winning window
    if (opt_.max_shear > 0 && opt_.shear_step > 0) {
      // Sheared windows around the upright minimum: the lowest SAD over shear and column wins,
      // the upright window on ties (shears tried in order of size).
      const int reach = static_cast<int>(std::ceil(opt_.max_shear * h));
      const int c_lo = std::max(col - kShearColumns, h + reach + 1);
      const int c_hi = std::min(col + kShearColumns, R.cols - h - reach - 2);
      const int steps = static_cast<int>(std::floor(opt_.max_shear / opt_.shear_step + 1e-9));
      double best_cost = c1;
      for (int s = 1; s <= steps && c_lo <= c_hi; ++s) {
        for (const double g : {s * opt_.shear_step, -s * opt_.shear_step}) {
          SadRowSheared(L, R, xl, c_lo - 1, yl, h, g, c_hi - c_lo + 3, &acc);  // columns c_lo-1 .. c_hi+1
          for (int k = 1; k + 1 < c_hi - c_lo + 3; ++k) {
            if (acc[k] < best_cost) {
              best_cost = acc[k];
              col = c_lo - 1 + k;
              c0 = acc[k - 1];
              c1 = acc[k];
              c2 = acc[k + 1];
              shear = g;
            }
          }
        }
      }
    }
    const double delta = SubPixel(c0, c1, c2);
    if (std::abs(delta) > 1) continue;
    const double u_r = grid.ToImageX(col + delta);
    const double disparity = kl.pt.x - u_r;
    if (disparity <= 0 || disparity > max_disp) continue;
    if (opt_.lr_check_px > 0) {
      // Back from the right patch at `col` along the left row, over the whole disparity range (the
      // same window, its shear mirrored onto the left image): the minimum should be the left
      // feature's column, less the forward match's sub-pixel offset. A match that is not mutual
      // (the feature's surface hidden from the right camera, ambiguous texture) is dropped. After
      // the range test, which is cheap: this searches a whole row.
      const int reach = static_cast<int>(std::lround(std::abs(shear) * h));
      const int b_lo = std::max(col + 1, h + reach + 1);
      const int b_hi = std::min(col + static_cast<int>(std::floor(max_disp / grid.scale_x())), L.cols - h - reach - 2);
      if (b_hi >= b_lo) {
        const int n = b_hi - b_lo + 3;  // columns b_lo-1 .. b_hi+1
        if (shear == 0) {
          SadRow(R, L, col, b_lo - 1, yl, h, n, &acc, &sad);
        } else {
          SadRowSheared(R, L, col, b_lo - 1, yl, h, -shear, n, &acc);
          sad.assign(acc.begin(), acc.end());
        }
        const int k = static_cast<int>(std::min_element(sad.begin() + 1, sad.end() - 1) - sad.begin());
        const double back = b_lo - 1 + k + SubPixel(sad[k - 1], sad[k], sad[k + 1]);
        if (std::abs(back - (xl - delta)) > opt_.lr_check_px) continue;
      }
    }
    best_sad[i] = c1;
    out[i].right_index = best_j;
    out[i].u_right = static_cast<float>(u_r);
    const double depth = fx * baseline_m / disparity;
    if (depth < opt_.max_depth_baselines * baseline_m) out[i].depth_m = static_cast<float>(depth);
  }
  // Patches that still differ much more than the typical match are wrong matches (repeated
  // texture, occlusion): drop those above a multiple of the median SAD.
  std::vector<double> sads;
  for (double v : best_sad) if (v >= 0) sads.push_back(v);
  if (!sads.empty()) {
    std::nth_element(sads.begin(), sads.begin() + sads.size() / 2, sads.end());
    const double limit = opt_.sad_outlier_factor * sads[sads.size() / 2];
    for (size_t i = 0; i < out.size(); ++i) {
      if (best_sad[i] > limit) out[i] = StereoMatch{};
    }
  }
  return out;
}

}  // namespace viqu::slam

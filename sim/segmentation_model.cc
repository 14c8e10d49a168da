#include "sim/segmentation_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"

namespace viqu::sim {
namespace {

constexpr int kMaxId = std::numeric_limits<uint16_t>::max();  // highest instance id

bool IsDetectable(const viqu::SegmentInstance& inst) {
  return inst.id != 0 && inst.category != viqu::Category::kBackground &&
         inst.category != viqu::Category::kRobot;
}

// One detectable instance: its pixels in the ideal image, and what steps 3-4 make of it.
struct Kept {
  uint16_t id = 0;
  viqu::Category category = viqu::Category::kBackground;  // as reported (step 3)
  int radius_px = 0;  // growth (> 0) or shrinking (< 0) of its mask, step 4 (px)
  int area_px = 0;    // its pixels in the ideal image (px)
  int min_x = std::numeric_limits<int>::max(), min_y = std::numeric_limits<int>::max();  // (px)
  int max_x = -1, max_y = -1;                                                            // (px)
  std::vector<float> depths_m;  // finite positive depths of its pixels (m)
  double depth_m = std::numeric_limits<double>::infinity();  // median of depths_m (m)
};

// Seed of stream k: output k of a SplitMix64 generator started at `seed`.
uint64_t SplitMix64Output(uint64_t seed, uint64_t k) {
  uint64_t z = seed + k * 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from exactly one engine output (its top 53 bits).
double Uniform01(std::mt19937_64& g) {
  return static_cast<double>(g() >> 11) * (1.0 / 9007199254740992.0);  // 2^-53
}

// Uniform integer in [0, n), n >= 1, from exactly one engine output.
int UniformIndex(std::mt19937_64& g, int n) {
  return std::min(n - 1, static_cast<int>(Uniform01(g) * n));
}

// The categories a detector may confuse (step 3) and the movable ones of spurious masks (step 5).
constexpr std::array<viqu::Category, 4> kConfusable = {viqu::Category::kPerson, viqu::Category::kBox,
                                                       viqu::Category::kBall, viqu::Category::kFurniture};
constexpr std::array<viqu::Category, 3> kMovable = {viqu::Category::kPerson, viqu::Category::kBox,
                                                    viqu::Category::kBall};

// The `index`-th (0..2) of the confusable categories other than `c` (a confusable one).
viqu::Category OtherCategory(viqu::Category c, int index) {
  for (const viqu::Category other : kConfusable) {
    if (other == c) continue;
    if (index-- == 0) return other;
  }
  return c;  // not reached for a confusable `c`
}

cv::Mat SquareKernel(int r) {
  return cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1));
}

}  // namespace

SegmentationModel::SegmentationModel(const viqu::SegmentationConfig& config, uint64_t seed)
    : config_(config),
      rng_(seed),
      category_rng_(SplitMix64Output(seed, 1)),
      jitter_rng_(SplitMix64Output(seed, 2)),
      spurious_rng_(SplitMix64Output(seed, 3)) {
  const std::pair<const char*, double> rates[] = {{"miss_rate", config.miss_rate},
                                                  {"false_positive_rate", config.false_positive_rate},
                                                  {"wrong_category_rate", config.wrong_category_rate}};
  for (const auto& [name, rate] : rates) {
    if (!(rate >= 0.0 && rate <= 1.0)) {
      std::ostringstream msg;
      msg << "SegmentationModel: " << name << " must be in [0, 1], got " << rate;
      throw viqu::InputError(msg.str());
    }
  }
  if (config.dilate_px < 0 || config.latency_frames < 0) {
    std::ostringstream msg;
    msg << "SegmentationModel: dilate_px and latency_frames must be >= 0, got "
        << config.dilate_px << " and " << config.latency_frames;
    throw viqu::InputError(msg.str());
  }
  if (config.min_area_px < 0 || config.boundary_jitter_px < 0) {
    std::ostringstream msg;
    msg << "SegmentationModel: min_area_px and boundary_jitter_px must be >= 0, got "
        << config.min_area_px << " and " << config.boundary_jitter_px;
    throw viqu::InputError(msg.str());
  }
}

SegmentationModel::Detection SegmentationModel::Detect(const viqu::StereoFrame& frame) {
  const cv::Mat& ideal = frame.left_instance_id;

  // The highest input id so far (step 5), over the image and the list.
  if (!ideal.empty()) {
    double max_pixel_id = 0;
    cv::minMaxIdx(ideal, nullptr, &max_pixel_id);
    max_input_id_ = std::max(max_input_id_, static_cast<int>(max_pixel_id));
  }
  for (const auto& inst : frame.instances) max_input_id_ = std::max<int>(max_input_id_, inst.id);

  std::vector<const viqu::SegmentInstance*> detectable;
  for (const auto& inst : frame.instances) {
    if (IsDetectable(inst)) detectable.push_back(&inst);
  }
  std::sort(detectable.begin(), detectable.end(),
            [](const auto* a, const auto* b) { return a->id < b->id; });
  detectable.erase(std::unique(detectable.begin(), detectable.end(),
                               [](const auto* a, const auto* b) { return a->id == b->id; }),
                   detectable.end());

  // One pass over the ideal image: visible area, bounding box and depths of each detectable
  // instance (depths only when some mask may grow).
  std::vector<int> slot(kMaxId + 1, -1);  // per id: index into `stats`, or -1
  std::vector<Kept> stats(detectable.size());
  for (size_t i = 0; i < detectable.size(); ++i) {
    slot[detectable[i]->id] = static_cast<int>(i);
    stats[i].id = detectable[i]->id;
  }
  const bool want_depth = GrowsMasks(config_) && !detectable.empty() &&
                          !frame.left_depth_m.empty() && frame.left_depth_m.type() == CV_32FC1 &&
                          frame.left_depth_m.size() == ideal.size();
  for (int y = 0; y < ideal.rows && !detectable.empty(); ++y) {
    const uint16_t* row = ideal.ptr<uint16_t>(y);
    const float* depth_row = want_depth ? frame.left_depth_m.ptr<float>(y) : nullptr;
    for (int x = 0; x < ideal.cols; ++x) {
      const int s = slot[row[x]];
      if (s < 0) continue;
      Kept& k = stats[static_cast<size_t>(s)];
      ++k.area_px;
      k.min_x = std::min(k.min_x, x);
      k.max_x = std::max(k.max_x, x);
      k.min_y = std::min(k.min_y, y);
      k.max_y = std::max(k.max_y, y);
      if (depth_row != nullptr && std::isfinite(depth_row[x]) && depth_row[x] > 0.0f) {
        k.depths_m.push_back(depth_row[x]);
      }
    }
  }

  // Steps 1-4 draw per detectable id in ascending order, each from its own stream.
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int jitter = config_.boundary_jitter_px;
  std::vector<bool> dropped(detectable.size(), false);
  for (size_t i = 0; i < detectable.size(); ++i) {
    const viqu::SegmentInstance& inst = *detectable[i];
    Kept& k = stats[i];
    const bool missed = uniform(rng_) < config_.miss_rate;                        // step 1
    const bool relabel = Uniform01(category_rng_) < config_.wrong_category_rate;  // step 3
    const int other = UniformIndex(category_rng_, 3);                             // step 3
    const int jitter_px = UniformIndex(jitter_rng_, 2 * jitter + 1) - jitter;     // step 4
    dropped[i] = missed || k.area_px < config_.min_area_px;                       // steps 1-2
    k.category = relabel ? OtherCategory(inst.category, other) : inst.category;
    k.radius_px = config_.dilate_px + jitter_px;
  }

  Detection out;
  for (const auto& inst : frame.instances) {
    const int s = slot[inst.id];
    if (s >= 0 && dropped[static_cast<size_t>(s)]) continue;
    out.instances.push_back(inst);
    if (s >= 0) out.instances.back().category = stats[static_cast<size_t>(s)].category;
  }

  // Dropped pixels become 0; the kept instances go on to step 4.
  out.instance_id = ideal.clone();
  std::vector<Kept> kept;
  kept.reserve(stats.size());
  for (size_t i = 0; i < stats.size(); ++i) {
    Kept& k = stats[i];
    if (!dropped[i]) {
      kept.push_back(std::move(k));
    } else if (k.max_x >= 0) {
      cv::Mat ids = out.instance_id(
          cv::Rect(cv::Point(k.min_x, k.min_y), cv::Point(k.max_x + 1, k.max_y + 1)));
      ids.setTo(0, ids == k.id);
    }
  }
  const bool any_growth =
      std::any_of(kept.begin(), kept.end(), [](const Kept& k) { return k.radius_px > 0; });
  const bool any_shrink =
      std::any_of(kept.begin(), kept.end(), [](const Kept& k) { return k.radius_px < 0; });

  const cv::Rect image_rect(0, 0, out.instance_id.cols, out.instance_id.rows);
  auto roi_of = [&image_rect](const Kept& k, int r) {
    return cv::Rect(cv::Point(k.min_x - r, k.min_y - r), cv::Point(k.max_x + r + 1, k.max_y + r + 1)) &
           image_rect;
  };

  // Step 4a: shrink. Erosion only looks at the instance's own pixels, so the order is free.
  if (any_shrink) {
    std::vector<bool> vanished(kMaxId + 1, false);
    bool any_vanished = false;
    for (const Kept& k : kept) {
      if (k.radius_px >= 0 || k.max_x < 0) continue;
      const int r = -k.radius_px;
      cv::Mat ids = out.instance_id(roi_of(k, r));
      const cv::Mat own = ids == k.id;  // a new matrix: erode sees nothing outside the image
      cv::Mat shrunk;
      cv::erode(own, shrunk, SquareKernel(r));  // default border: beyond the image counts as own
      ids.setTo(0, own & ~shrunk);
      if (cv::countNonZero(shrunk) == 0) {
        vanished[k.id] = true;
        any_vanished = true;
      }
    }
    if (any_vanished) {
      out.instances.erase(std::remove_if(out.instances.begin(), out.instances.end(),
                                         [&vanished](const auto& s) { return vanished[s.id]; }),
                          out.instances.end());
    }
  }

  // Step 4b: grow, nearest instance first (then lower id), each claiming only zero pixels.
  if (any_growth) {
    for (Kept& k : kept) {
      if (k.depths_m.empty()) continue;
      auto mid = k.depths_m.begin() + static_cast<std::ptrdiff_t>(k.depths_m.size() / 2);
      std::nth_element(k.depths_m.begin(), mid, k.depths_m.end());
      k.depth_m = *mid;
      std::vector<float>().swap(k.depths_m);
    }
    std::sort(kept.begin(), kept.end(), [](const Kept& a, const Kept& b) {
      return a.depth_m != b.depth_m ? a.depth_m < b.depth_m : a.id < b.id;
    });
    for (const Kept& k : kept) {
      if (k.radius_px <= 0 || k.max_x < 0) continue;  // not growing, or listed but not in the image
      const int r = k.radius_px;
      cv::Mat ids = out.instance_id(roi_of(k, r));
      cv::Mat own = ids == k.id;
      cv::Mat grown;
      cv::dilate(own, grown, SquareKernel(r));
      cv::Mat claim = grown & (ids == 0);
      ids.setTo(k.id, claim);
    }
  }

  AddSpurious(&out);
  return out;
}

void SegmentationModel::AddSpurious(Detection* out) {
  // Six draws per frame, whatever happens below.
  const bool fire = Uniform01(spurious_rng_) < config_.false_positive_rate;
  const viqu::Category category = kMovable[static_cast<size_t>(UniformIndex(spurious_rng_, 3))];
  const double u_centre = Uniform01(spurious_rng_);
  const int axis_choices = kSpuriousMaxSemiAxisPx - kSpuriousMinSemiAxisPx + 1;
  const int semi_a_px = kSpuriousMinSemiAxisPx + UniformIndex(spurious_rng_, axis_choices);
  const int semi_b_px = kSpuriousMinSemiAxisPx + UniformIndex(spurious_rng_, axis_choices);
  const double angle_deg = 180.0 * Uniform01(spurious_rng_);
  if (!fire || max_input_id_ >= kMaxId) return;  // no id left above the input's

  cv::Mat& ids = out->instance_id;
  const int64_t background = static_cast<int64_t>(ids.total()) - cv::countNonZero(ids);
  if (background == 0) return;
  // The centre: background pixel number `target` in raster order.
  const int64_t target =
      std::min(background - 1, static_cast<int64_t>(u_centre * static_cast<double>(background)));
  int centre_x = -1, centre_y = -1;
  int64_t seen = 0;
  for (int y = 0; y < ids.rows && centre_x < 0; ++y) {
    const uint16_t* row = ids.ptr<uint16_t>(y);
    for (int x = 0; x < ids.cols; ++x) {
      if (row[x] != 0) continue;
      if (seen++ == target) {
        centre_x = x;
        centre_y = y;
        break;
      }
    }
  }

  if (next_spurious_id_ <= max_input_id_) next_spurious_id_ = kMaxId;  // wrap
  const auto id = static_cast<uint16_t>(next_spurious_id_--);
  ++spurious_count_;

  const int reach = kSpuriousMaxSemiAxisPx;
  const cv::Rect roi = cv::Rect(centre_x - reach, centre_y - reach, 2 * reach + 1, 2 * reach + 1) &
                       cv::Rect(0, 0, ids.cols, ids.rows);
  cv::Mat blob = cv::Mat::zeros(roi.size(), CV_8UC1);
  cv::ellipse(blob, cv::Point(centre_x - roi.x, centre_y - roi.y), cv::Size(semi_a_px, semi_b_px),
              angle_deg, 0.0, 360.0, cv::Scalar(255), cv::FILLED, cv::LINE_8);
  cv::Mat sub = ids(roi);
  sub.setTo(id, blob & (sub == 0));
  out->instances.push_back(
      viqu::SegmentInstance{id, category, "spurious_" + std::to_string(spurious_count_)});
}

void SegmentationModel::Apply(viqu::StereoFrame* frame) {
  if (frame == nullptr) throw viqu::InputError("SegmentationModel::Apply: null frame");
  if (frame->left_instance_id.empty()) return;
  if (frame->left_instance_id.type() != CV_16UC1) {
    std::ostringstream msg;
    msg << "SegmentationModel::Apply: left_instance_id must be CV_16UC1, got OpenCV type "
        << frame->left_instance_id.type();
    throw viqu::InputError(msg.str());
  }
  Detection detection = Detect(*frame);
  if (config_.latency_frames > 0) {
    pending_.push_back(std::move(detection));
    if (static_cast<int>(pending_.size()) <= config_.latency_frames) {
      // Nothing has arrived yet: an empty mask.
      detection = Detection{};
      detection.instance_id = cv::Mat::zeros(frame->left_instance_id.size(), CV_16UC1);
      for (const auto& inst : frame->instances) {
        if (inst.id == 0) detection.instances.push_back(inst);
      }
    } else {
      detection = std::move(pending_.front());
      pending_.pop_front();
    }
  }
  frame->left_instance_id = detection.instance_id;
  frame->instances = std::move(detection.instances);
}

}  // namespace viqu::sim

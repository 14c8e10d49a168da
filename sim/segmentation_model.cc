#include "sim/segmentation_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"

namespace viqu::sim {
namespace {

bool IsDetectable(const viqu::SegmentInstance& inst) {
  return inst.id != 0 && inst.category != viqu::Category::kBackground &&
         inst.category != viqu::Category::kRobot;
}

// What the pixel pass does with an id: leave it, zero it, or account it to a kept instance.
constexpr int kLeave = -1;
constexpr int kDrop = -2;

// One kept detectable instance during dilation.
struct Kept {
  uint16_t id = 0;
  int min_x = std::numeric_limits<int>::max(), min_y = std::numeric_limits<int>::max();  // (px)
  int max_x = -1, max_y = -1;                                                            // (px)
  std::vector<float> depths_m;  // finite positive depths of its pixels (m)
  double depth_m = std::numeric_limits<double>::infinity();  // median of depths_m (m)
};

}  // namespace

SegmentationModel::SegmentationModel(const viqu::SegmentationConfig& config, uint64_t seed)
    : config_(config), rng_(seed) {
  if (!(config.miss_rate >= 0.0 && config.miss_rate <= 1.0)) {
    std::ostringstream msg;
    msg << "SegmentationModel: miss_rate must be in [0, 1], got " << config.miss_rate;
    throw viqu::InputError(msg.str());
  }
  if (config.dilate_px < 0 || config.latency_frames < 0) {
    std::ostringstream msg;
    msg << "SegmentationModel: dilate_px and latency_frames must be >= 0, got "
        << config.dilate_px << " and " << config.latency_frames;
    throw viqu::InputError(msg.str());
  }
}

SegmentationModel::Detection SegmentationModel::Detect(const viqu::StereoFrame& frame) {
  const cv::Mat& ideal = frame.left_instance_id;

  // Step 1: decide the misses, one draw per detectable id in ascending order.
  std::vector<const viqu::SegmentInstance*> detectable;
  for (const auto& inst : frame.instances) {
    if (IsDetectable(inst)) detectable.push_back(&inst);
  }
  std::sort(detectable.begin(), detectable.end(),
            [](const auto* a, const auto* b) { return a->id < b->id; });
  detectable.erase(std::unique(detectable.begin(), detectable.end(),
                               [](const auto* a, const auto* b) { return a->id == b->id; }),
                   detectable.end());
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<int> action(65536, kLeave);  // per id: kLeave, kDrop or index into `kept`
  std::vector<Kept> kept;
  for (const auto* inst : detectable) {
    if (uniform(rng_) < config_.miss_rate) {
      action[inst->id] = kDrop;
    } else {
      action[inst->id] = static_cast<int>(kept.size());
      kept.emplace_back();
      kept.back().id = inst->id;
    }
  }

  Detection out;
  for (const auto& inst : frame.instances) {
    if (action[inst.id] != kDrop) out.instances.push_back(inst);
  }

  // One pass: zero dropped pixels; bounding box and depths of kept detectable instances.
  const bool want_depth = config_.dilate_px > 0 && !frame.left_depth_m.empty() &&
                          frame.left_depth_m.type() == CV_32FC1 &&
                          frame.left_depth_m.size() == ideal.size();
  out.instance_id = ideal.clone();
  for (int y = 0; y < out.instance_id.rows; ++y) {
    uint16_t* row = out.instance_id.ptr<uint16_t>(y);
    const float* depth_row = want_depth ? frame.left_depth_m.ptr<float>(y) : nullptr;
    for (int x = 0; x < out.instance_id.cols; ++x) {
      const int a = action[row[x]];
      if (a == kLeave) continue;
      if (a == kDrop) {
        row[x] = 0;
        continue;
      }
      Kept& k = kept[a];
      k.min_x = std::min(k.min_x, x);
      k.max_x = std::max(k.max_x, x);
      k.min_y = std::min(k.min_y, y);
      k.max_y = std::max(k.max_y, y);
      if (depth_row != nullptr && std::isfinite(depth_row[x]) && depth_row[x] > 0.0f) {
        k.depths_m.push_back(depth_row[x]);
      }
    }
  }
  if (config_.dilate_px == 0 || kept.empty()) return out;

  // Step 2: dilate, nearest instance first (then lower id), each claiming only zero pixels.
  for (Kept& k : kept) {
    if (k.depths_m.empty()) continue;
    auto mid = k.depths_m.begin() + k.depths_m.size() / 2;
    std::nth_element(k.depths_m.begin(), mid, k.depths_m.end());
    k.depth_m = *mid;
    std::vector<float>().swap(k.depths_m);
  }
  std::sort(kept.begin(), kept.end(), [](const Kept& a, const Kept& b) {
    return a.depth_m != b.depth_m ? a.depth_m < b.depth_m : a.id < b.id;
  });
  const int r = config_.dilate_px;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1));
  const cv::Rect image_rect(0, 0, out.instance_id.cols, out.instance_id.rows);
  for (const Kept& k : kept) {
    if (k.max_x < 0) continue;  // listed but not in the image
    const cv::Rect roi = cv::Rect(cv::Point(k.min_x - r, k.min_y - r),
                                  cv::Point(k.max_x + r + 1, k.max_y + r + 1)) & image_rect;
    cv::Mat ids = out.instance_id(roi);
    cv::Mat own = ids == k.id;
    cv::Mat grown;
    cv::dilate(own, grown, kernel);
    cv::Mat claim = grown & (ids == 0);
    ids.setTo(k.id, claim);
  }
  return out;
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

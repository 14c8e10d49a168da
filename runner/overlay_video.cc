#include "runner/overlay_video.h"

#include <cstdio>
#include <map>

#include <opencv2/imgproc.hpp>

#include "common/atomic_file.h"
#include "common/errors.h"

namespace viqu::runner {
namespace {

// Colours (BGR).
const cv::Scalar kTracked(60, 200, 60), kNew(230, 200, 0), kDropped(40, 40, 230), kUnmatched(0, 210, 230);
constexpr double kMaskAlpha = 0.35;  // tint of an object's mask over the image

// A distinct, stable colour per instance id (golden-angle hue steps).
cv::Vec3b ObjectColour(uint16_t id) {
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((id * 137) % 180, 200, 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr.at<cv::Vec3b>(0, 0);
}

void Label(cv::Mat* img, const std::string& text, cv::Point at, const cv::Scalar& colour, double scale = 0.45) {
  int base = 0;
  const cv::Size sz = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
  at.x = std::max(0, std::min(at.x, img->cols - sz.width - 2));
  at.y = std::max(sz.height + 2, std::min(at.y, img->rows - base - 2));
  cv::rectangle(*img, cv::Point(at.x - 1, at.y - sz.height - 2), cv::Point(at.x + sz.width + 1, at.y + base), cv::Scalar::all(0),
                cv::FILLED);
  cv::putText(*img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

}  // namespace

OverlayVideo::OverlayVideo(const std::string& path, double fps, int width, int height)
    : path_(path), tmp_(TempPathFor(path) + ".mp4") {
  writer_.open(tmp_, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps, cv::Size(width, height));
  if (!writer_.isOpened()) throw RunError("cannot open a video writer for " + path + " (OpenCV without an mp4 encoder?)");
}

OverlayVideo::~OverlayVideo() {
  if (!done_) std::remove(tmp_.c_str());
}

cv::Mat OverlayVideo::Draw(const StereoFrame& frame, const slam::TrackResult* track, double error_m) {
  cv::Mat img;
  cv::cvtColor(frame.left_rgb, img, cv::COLOR_RGB2BGR);
  // Masks, tinted per object, labelled with name and state.
  if (!frame.left_instance_id.empty()) {
    std::map<uint16_t, bool> dynamic;
    if (track) {
      for (const slam::ObjectReport& o : track->objects) dynamic[o.id] = o.dynamic;
    }
    for (const SegmentInstance& inst : frame.instances) {
      if (inst.id == 0) continue;
      const cv::Mat mask = frame.left_instance_id == inst.id;
      const cv::Rect box = cv::boundingRect(mask);
      if (box.empty()) continue;
      // Blended within the object's box only: a frame may hold many objects.
      const cv::Vec3b c = ObjectColour(inst.id);
      cv::Mat roi = img(box), blended;
      cv::addWeighted(roi, 1 - kMaskAlpha, cv::Mat(box.size(), img.type(), cv::Scalar(c[0], c[1], c[2])), kMaskAlpha, 0,
                      blended);
      blended.copyTo(roi, mask(box));
      const auto it = dynamic.find(inst.id);
      const bool is_dynamic = it != dynamic.end() && it->second;
      if (is_dynamic) cv::rectangle(img, box, kDropped, 2);
      const std::string state = it == dynamic.end() ? "" : is_dynamic ? ": dynamic" : ": static";
      Label(&img, inst.name + state, cv::Point(box.x, box.y - 3), is_dynamic ? kDropped : cv::Scalar(c[0], c[1], c[2]));
    }
  }
  if (track) {
    for (const slam::FeatureMark& m : track->marks) {
      const cv::Scalar& colour = m.fate == slam::FeatureFate::kTracked ? kTracked
                                 : m.fate == slam::FeatureFate::kNew   ? kNew
                                 : m.fate == slam::FeatureFate::kDropped ? kDropped
                                                                         : kUnmatched;
      cv::circle(img, cv::Point(cvRound(m.x), cvRound(m.y)), 2, colour, cv::FILLED, cv::LINE_AA);
    }
  }
  // The frame's status in the top-left corner, the colour key below it.
  char line[160];
  if (track) {
    char err[32] = "";
    if (error_m >= 0) std::snprintf(err, sizeof err, ", error %.1f mm", error_m * 1e3);
    std::snprintf(line, sizeof line, "t %.2f s  %s  inliers %d%s", frame.t_ns * 1e-9, slam::TrackStatusName(track->status),
                  track->inliers, err);
  } else {
    std::snprintf(line, sizeof line, "t %.2f s  (no SLAM)", frame.t_ns * 1e-9);
  }
  // Text sized for a 640 px wide image, scaled with the width.
  const double s = std::max(0.3, img.cols / 640.0);
  Label(&img, line, cv::Point(4, static_cast<int>(16 * s)), cv::Scalar::all(255), 0.5 * s);
  if (track) {
    int x = 4;
    for (const auto& [name, colour] : {std::pair<const char*, cv::Scalar>{"tracked", kTracked}, {"new", kNew},
                                       {"dropped (dynamic)", kDropped}, {"unmatched", kUnmatched}}) {
      Label(&img, name, cv::Point(x, static_cast<int>(34 * s)), colour, 0.4 * s);
      x += static_cast<int>(10 * s) + cv::getTextSize(name, cv::FONT_HERSHEY_SIMPLEX, 0.4 * s, 1, nullptr).width;
    }
  }
  return img;
}

void OverlayVideo::Add(const StereoFrame& frame, const slam::TrackResult* track, double error_m) {
  writer_.write(Draw(frame, track, error_m));
}

void OverlayVideo::Finish() {
  writer_.release();
  CommitTempFile(tmp_, path_);
  done_ = true;
}

}  // namespace viqu::runner
